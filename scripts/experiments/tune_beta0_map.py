#!/usr/bin/env python3
"""Chooses the adaptive filter's mu -> beta0 map on drives the experiment suite does not use:
the suite's scenarios on other seeds, run with beta0 fixed at 10, 30 and 60 deg and with each
candidate map, and for each candidate the ratio of its t_err to the best fixed threshold's per
scenario (mean over the seeds), the worst ratio and the mean t_err. Also each scenario's mean mu
and the spread of mu over its scans (mu does not depend on the map).

  tune_beta0_map.py --bin DIR --root DIR --data DIR --work DIR --sensor hdl64e|vlp16
                    [--seeds 4,5,6] [--jobs N] MAP [MAP ...]

A MAP is MIN-MAX[:STRICT-LENIENT][+WEIGHT,REFERENCE[@FLOOR]][!KEEP]: beta0_min_deg and
beta0_max_deg, the knots mu_strict_below and mu_lenient_above (0-1 when left out),
mu_structure_weight and mu_structure_reference (weight 0 when left out),
fragment_smoothness_floor (1 when left out) and mu_keep_every_cluster (never when left out), e.g.
10-60:0.3-0.55, 10-60:0.3-0.45+1.5,0.25@0.45 or 2-10!0.9.
"""

import argparse
import csv
import pathlib
import statistics
import sys

import suite

FIXED = ["fixed 10", "fixed 30", "fixed 60"]


def parse_map(text):
    """'10-60:0.3-0.55+1.5,0.25@0.45!0.9' -> ('map 10-60:0.3-0.55+1.5,0.25@0.45!0.9',
    {ambient_filter key: value})."""
    try:
        spec, _, keep = text.partition("!")
        keep = float(keep) if keep else 2.0
        spec, _, structure = spec.partition("+")
        structure, _, floor = structure.partition("@")
        weight, reference = (float(v) for v in structure.split(",")) if structure else (0.0, 0.3)
        floor = float(floor) if floor else 1.0
        ends, _, knots = spec.partition(":")
        low, high = (float(v) for v in ends.split("-"))
        strict, lenient = (float(v) for v in knots.split("-")) if knots else (0.0, 1.0)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"map {text!r}: expected MIN-MAX[:STRICT-LENIENT][+WEIGHT,REFERENCE[@FLOOR]][!KEEP], "
            "e.g. 10-60:0.3-0.55+1.5,0.25@0.45 or 2-10!0.9")
    if not (0 < low <= high < 90 and 0 <= strict < lenient <= 1 and 0 <= weight <= 10
            and 0 <= reference <= 1 and 0 <= floor <= 1 and 0 <= keep <= 2):
        raise argparse.ArgumentTypeError(f"map {text!r}: expected 0 < MIN <= MAX < 90, "
                                         "0 <= STRICT < LENIENT <= 1, 0 <= WEIGHT <= 10 and "
                                         "0 <= REFERENCE, FLOOR <= 1, 0 <= KEEP <= 2")
    return f"map {text}", {"beta0_min_deg": f"{low:g}", "beta0_max_deg": f"{high:g}",
                           "mu_strict_below": f"{strict:g}", "mu_lenient_above": f"{lenient:g}",
                           "mu_structure_weight": f"{weight:g}",
                           "mu_structure_reference": f"{reference:g}",
                           "fragment_smoothness_floor": f"{floor:g}",
                           "mu_keep_every_cluster": f"{keep:g}"}


def scan_mus(run_folder):
    """mu of every scan with a valid mu."""
    with open(run_folder / "degeneration.csv") as f:
        return [float(row["mu"]) for row in csv.DictReader(f) if row["valid"] == "1"]


def mu_text(results, scenario, first_map):
    """Mean mu over the scenario's scans (every seed), with its 10th and 90th percentiles."""
    mus = [mu for r in results if r["scenario"] == scenario and r["method"] == first_map
           for mu in scan_mus(pathlib.Path(r["output"]))]
    if len(mus) < 2:
        return "-"
    deciles = statistics.quantiles(mus, n=10)
    return f"{statistics.mean(mus):.2f} ({deciles[0]:.2f}-{deciles[-1]:.2f})"


def report(results, maps):
    scenarios = list(dict.fromkeys(r["scenario"] for r in results))
    t_err = {}
    for r in results:
        t_err.setdefault((r["scenario"], r["method"]), []).append(r["t_err"])
    mean = {key: statistics.mean(values) for key, values in t_err.items()}
    methods = FIXED + maps
    print("| scenario | mu (10-90 %) | " + " | ".join(methods) + " |")
    print("|---" * (len(methods) + 2) + "|")
    ratios = {m: [] for m in maps}
    for scenario in scenarios:
        best = min(mean[(scenario, m)] for m in FIXED)
        cells = []
        for m in methods:
            value = mean[(scenario, m)]
            if m in maps:
                ratios[m].append(value / best)
                cells.append(f"{value:.3f} ({value / best:.2f})")
            else:
                cells.append(f"{value:.3f}")
        print(f"| {scenario} | {mu_text(results, scenario, maps[0])} | " + " | ".join(cells) + " |")
    fixed_means = [statistics.mean(mean[(s, m)] for s in scenarios) for m in FIXED]
    print("\nmean t_err over the scenarios, fixed 10 / 30 / 60: "
          + " / ".join(f"{v:.3f}" for v in fixed_means))
    for m in maps:
        scenario_means = statistics.mean(mean[(s, m)] for s in scenarios)
        print(f"{m}: worst ratio {max(ratios[m]):.2f}, "
              f"mean ratio {statistics.mean(ratios[m]):.2f}, "
              f"mean t_err {scenario_means:.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    suite.add_runner_arguments(parser)
    parser.add_argument("--sensor", required=True, choices=sorted(suite.SENSORS))
    parser.add_argument("--seeds", default="4,5,6", help="comma-separated (default 4,5,6)")
    parser.add_argument("maps", nargs="+", type=parse_map, metavar="MAP")
    args = parser.parse_args()
    args.foliage_density = None
    try:
        args.seeds = [int(seed) for seed in args.seeds.split(",")]
    except ValueError:
        parser.error(f"--seeds {args.seeds}: expected comma-separated integers, e.g. 4,5,6")
    if set(args.seeds) & set(suite.SUITE_SEEDS):
        parser.error(f"seeds {suite.SUITE_SEEDS} are the suite's: choose the map on others")
    runner = suite.Runner(args)
    runner.methods = {m: suite.METHODS[m] for m in FIXED}
    runner.config_changes = {}
    for name, changes in args.maps:
        runner.methods[name] = ["--adaptive"]
        runner.config_changes[name] = changes
    try:
        sensors = {args.sensor: suite.SENSORS[args.sensor]}
        results = runner.simulated_suite(False, args.seeds, sensors)
    except RuntimeError as error:
        sys.stderr.write(f"\ntune_beta0_map: {error}\n")
        return 1
    sys.stderr.write("\n")
    report(results, [name for name, _ in args.maps])
    return 0


if __name__ == "__main__":
    sys.exit(main())
