#!/usr/bin/env python3
"""Checks the house rules the compiler does not: core stages include only earlier stages (and
common/, spatial/), the core includes no ROS, simulator, I/O or evaluation header, and nothing in
the code or docs points at a path outside the checkout. Prints one line per breach; exits 1 if
there is any. Run by scripts/test.sh."""

import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
STAGES = ["common", "spatial", "projection", "clustering", "ambient", "motion_sensors",
          "odometry", "mapping", "loop_closure", "pipeline"]
SHARED = {"common", "spatial"}
INCLUDE = re.compile(r'#include [<"]adaptive_lego_loam/([a-z_]+)/(?:([a-z_]+)/)?[a-z_]+\.h[>"]')
OUTSIDE = re.compile(r"\.\./shared|/work/|/home/[a-z]")


def core_stage(path):
    parts = path.relative_to(ROOT).parts
    for base in (("include", "adaptive_lego_loam", "core"), ("src", "core")):
        if parts[:len(base)] == base and len(parts) > len(base) + 1:
            return parts[len(base)]
    return None


def include_problems(path, stage):
    problems = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if re.match(r'#include [<"](ros|sensor_msgs|nav_msgs|std_msgs|tf2|rosbag)/', line):
            problems.append(f"{path.relative_to(ROOT)}:{number}: the core includes ROS")
        match = INCLUDE.match(line)
        if not match:
            continue
        library, included = match.group(1), match.group(2)
        if library != "core":
            problems.append(f"{path.relative_to(ROOT)}:{number}: core/{stage} includes {library}/")
        elif included not in STAGES:
            problems.append(f"{path.relative_to(ROOT)}:{number}: unknown core folder {included}")
        elif included not in SHARED and STAGES.index(included) > STAGES.index(stage):
            problems.append(f"{path.relative_to(ROOT)}:{number}: core/{stage} includes the later "
                            f"stage core/{included}")
        elif stage in SHARED and included not in SHARED:
            problems.append(f"{path.relative_to(ROOT)}:{number}: core/{stage} includes the stage "
                            f"core/{included}")
        elif stage == "common" and included == "spatial":
            problems.append(f"{path.relative_to(ROOT)}:{number}: core/common includes core/spatial")
    return problems


def main():
    problems = []
    for path in sorted(ROOT.glob("include/adaptive_lego_loam/core/**/*.h")) + \
            sorted(ROOT.glob("src/core/**/*.cpp")):
        stage = core_stage(path)
        if stage is None:
            problems.append(f"{path.relative_to(ROOT)}: core file outside a stage folder")
        elif stage not in STAGES:
            problems.append(f"{path.relative_to(ROOT)}: unknown stage folder {stage}")
        else:
            problems += include_problems(path, stage)
    checked = ["include", "src", "test", "bench", "scripts", "launch", "config", "docs"]
    for folder in checked:
        for path in sorted((ROOT / folder).rglob("*")):
            if not path.is_file() or path.suffix not in {".h", ".cpp", ".py", ".sh", ".launch",
                                                          ".yaml", ".md", ".test", ".txt"}:
                continue
            if path == pathlib.Path(__file__).resolve() or "data" in path.relative_to(ROOT).parts:
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                if OUTSIDE.search(line):
                    problems.append(f"{path.relative_to(ROOT)}:{number}: points outside the "
                                    f"checkout: {line.strip()[:80]}")
    for readme in ["README.md", "DEVELOPERS.md"]:
        for number, line in enumerate((ROOT / readme).read_text().splitlines(), 1):
            if OUTSIDE.search(line):
                problems.append(f"{readme}:{number}: points outside the checkout: "
                                f"{line.strip()[:80]}")
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_layout: {len(problems)} problem(s)", file=sys.stderr)
        return 1
    print("check_layout: the stage order holds and nothing points outside the checkout")
    return 0


if __name__ == "__main__":
    sys.exit(main())
