#!/usr/bin/env python3
"""The experiment suite behind docs/RESULTS.md: simulated drives of every scenario (along real
KITTI trajectories where they fit) run with beta0 fixed at 10, 30 and 60 deg, adaptive, and
without segmentation; the real KITTI scans of the data folder; the clustering benchmark (the
paper's Table I) with both Euclidean criteria; mu from the range image and from a KD-tree along a
drive (Fig. 8). Runs JOBS programs at a time, shows progress, and writes WORK/results.json for
report.py. Called by scripts/run_experiments.sh, which builds first.

  suite.py --bin DIR --root DIR --data DIR --work DIR [--quick] [--jobs N] [--foliage-density X]
"""

import argparse
import concurrent.futures
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

METHODS = {  # name: run_sequence arguments
    "fixed 10": ["--beta0", "10"],
    "fixed 30": ["--beta0", "30"],
    "fixed 60": ["--beta0", "60"],
    "adaptive": ["--adaptive"],
    "adaptive d3": ["--adaptive"],
    "adaptive 10-60": ["--adaptive"],
    "adaptive mu alone": ["--adaptive"],
    "adaptive skeleton share": ["--adaptive"],
    "none": ["--no-segmentation"],
    "adaptive + IMU": ["--adaptive"],
    "adaptive + wheel": ["--adaptive"],
    "adaptive + IMU + wheel": ["--adaptive"],
}
# Methods that also take the drive's simulated motion sensors (lidar_sim --imu --wheel-odom): its
# sensors.yaml after the sensor's config (the true extrinsics and noise) and the samples.
MOTION_INPUTS = {
    "adaptive + IMU": ["imu"],
    "adaptive + wheel": ["wheel"],
    "adaptive + IMU + wheel": ["imu", "wheel"],
}
LIDAR_METHODS = [m for m in METHODS if m not in MOTION_INPUTS]
# Methods that also change the sensor's config: ambient_filter keys and their values. "adaptive
# d3" is the adaptive filter with the Euclidean criterion of the paper's text (the 3-D distance)
# and its 7 x 7 window (w 3), where the configs use the authors' range difference with w 5;
# "adaptive 10-60" is the paper's map, linear from 60 deg at mu 0 to 10 deg at mu 1, where the
# configs hold each end beyond a knot (docs/METHOD.md step 8), with mu from the normals alone
# and the size rule at every mu;
# "adaptive mu alone" is the configs' map on mu from the normals alone, without the shift by the
# structure share of the scene; "adaptive skeleton share" shifts mu by the skeleton's share alone,
# the smooth fragments not counted as structure (docs/METHOD.md step 7).
CONFIG_CHANGES = {
    "adaptive d3": {"euclidean_criterion": "distance", "euclidean_window": "3"},
    "adaptive 10-60": {"beta0_min_deg": "10.0", "beta0_max_deg": "60.0", "mu_strict_below": "0.0",
                       "mu_lenient_above": "1.0", "mu_structure_weight": "0",
                       "mu_keep_every_cluster": "2"},
    "adaptive mu alone": {"mu_structure_weight": "0"},
    "adaptive skeleton share": {"fragment_smoothness_floor": "1"},
}
SENSORS = {"hdl64e": "kitti.yaml", "vlp16": "vlp16.yaml"}
# What lidar_sim writes per scan (scans, labels), with a margin: 300 HDL-64E scans take 0.55 GB.
DRIVE_BYTES_PER_SCAN = {"hdl64e": 2.0e6, "vlp16": 0.5e6}


def scenarios(quick):
    """(name, lidar_sim scenario, KITTI sequence whose trajectory it drives or None, first frame,
    frames). The seeds vary the scene around the same trajectory. The tunnels take 600 scans: the
    drive enters at speed, brakes to 5 m/s inside and accelerates back (simulator.md)."""
    frames = 100 if quick else 300
    full = [
        ("green_highway", "green_highway", "01", 0, frames),
        ("busy_street", "busy_street", "04", 0, min(frames, 271)),
        ("urban_00", "urban", "00", 0, frames),
        ("urban_07", "urban", "07", 0, frames),
        ("highway", "highway", "01", 0, frames),
        ("loop", "loop", None, 0, frames + 100),
        ("vegetation", "vegetation", None, 0, frames),
        ("tunnel", "tunnel", None, 0, 2 * frames),
        ("bare_tunnel", "bare_tunnel", None, 0, 2 * frames),
        ("corridor", "corridor", None, 0, frames + 100),
    ]
    return full[:3] if quick else full


# Scenes where the LiDAR cannot see the motion along one direction.
DEGENERATE = ["tunnel", "bare_tunnel", "corridor"]

# Scenarios for one sensor only: the corridor is a robot's VLP-16 indoors.
SCENARIO_SENSORS = {"corridor": ["vlp16"]}


# The runs whose degenerate flag and covariance are scored against the simulator's truth.
DEGENERATION_METHODS = ["adaptive", "adaptive + IMU + wheel"]

SUITE_SEEDS = [1, 2, 3, 23, 24, 25]  # 4-22 chose the filter's settings (METHOD.md steps 7-8)


def seeds(quick):
    return SUITE_SEEDS[:1] if quick else SUITE_SEEDS


class Runner:
    def __init__(self, args):
        self.bin = pathlib.Path(args.bin)
        self.root = pathlib.Path(args.root)
        self.data = pathlib.Path(args.data)
        self.work = pathlib.Path(args.work)
        self.jobs = args.jobs
        self.foliage_density = args.foliage_density  # None: lidar_sim's default
        self.methods = METHODS
        self.config_changes = CONFIG_CHANGES
        self.done = 0
        self.total = 0
        self.started = time.time()

    def run(self, command, log):
        log.parent.mkdir(parents=True, exist_ok=True)
        with open(log, "w") as out:
            result = subprocess.run([str(c) for c in command], stdout=out, stderr=subprocess.STDOUT)
        if result.returncode != 0:
            tail = log.read_text().strip().splitlines()[-3:]
            raise RuntimeError(f"{command[0]} failed (log {log}): " + " | ".join(tail))

    def progress(self, what):
        self.done += 1
        elapsed = time.time() - self.started
        line = f"\rexperiments: {self.done}/{self.total} {what[:60]:<60} {elapsed / 60:5.1f} min"
        sys.stderr.write(line if sys.stderr.isatty() else line[1:] + "\n")
        sys.stderr.flush()

    def parallel(self, tasks):
        """Runs (description, function) pairs JOBS at a time; returns their results in order."""
        self.total += len(tasks)
        results = [None] * len(tasks)
        with concurrent.futures.ThreadPoolExecutor(self.jobs) as pool:
            futures = {pool.submit(task): i for i, (_, task) in enumerate(tasks)}
            for future in concurrent.futures.as_completed(futures):
                i = futures[future]
                results[i] = future.result()
                self.progress(tasks[i][0])
        return results

    # -- simulated drives ------------------------------------------------------------------

    def trajectory(self, sequence, first, frames):
        """KITTI poses and times of frames [first, first + frames), times from 0."""
        folder = self.work / "trajectories"
        folder.mkdir(parents=True, exist_ok=True)
        poses = folder / f"{sequence}_{first}_{frames}.txt"
        times = folder / f"{sequence}_{first}_{frames}_times.txt"
        if not poses.exists():
            lines = (self.data / "kitti_odometry" / "poses" / f"{sequence}.txt").read_text().split("\n")
            stamps = [float(t) for t in
                      (self.data / "kitti_odometry" / "times" / f"{sequence}.txt").read_text().split()]
            if first + frames > len(stamps):
                raise RuntimeError(f"KITTI {sequence} has {len(stamps)} frames, not {first + frames}")
            poses.write_text("\n".join(lines[first:first + frames]) + "\n")
            times.write_text("".join(f"{t - stamps[first]:.6f}\n" for t in stamps[first:first + frames]))
        return poses, times

    def drive_folder(self, name, sensor, seed):
        return self.work / "sequences" / f"{name}_{sensor}_s{seed}"

    def simulate(self, name, scenario, sequence, first, frames, sensor, seed):
        out = self.drive_folder(name, sensor, seed)
        if (out / "poses.txt").exists():
            return out
        command = [self.bin / "lidar_sim", "--scenario", scenario, "--sensor", sensor,
                   "--frames", frames, "--seed", seed, "--output", out, "--overwrite", "--imu",
                   "--wheel-odom"]
        if self.foliage_density is not None:
            command += ["--foliage-density", self.foliage_density]
        if sequence:
            poses, times = self.trajectory(sequence, first, frames)
            command += ["--trajectory", poses, "--trajectory-times", times]
        self.run(command, out.parent / f"{out.name}.log")
        return out

    def method_config(self, config, method):
        """The sensor's config with `method`'s ambient_filter changes, written under WORK."""
        changes = self.config_changes.get(method)
        if not changes:
            return config
        text = pathlib.Path(config).read_text()
        for key, value in changes.items():
            text, count = re.subn(rf"^(  {key}:\s*)\S+", rf"\g<1>{value}", text, flags=re.M)
            if count != 1:
                raise RuntimeError(f"{config}: no ambient_filter key {key} to set for {method}")
        out = self.work / "configs" / f"{pathlib.Path(config).stem}_{method.replace(' ', '')}.yaml"
        out.parent.mkdir(parents=True, exist_ok=True)
        if not out.exists() or out.read_text() != text:
            out.write_text(text)
        return out

    def odometry(self, sequence, config, method, out, gt=None, calib=None):
        """run_sequence with `method`, then evaluate_odometry; returns both JSONs' figures."""
        config = self.method_config(config, method)
        if not (out / "metrics.json").exists():
            inputs = []
            for sensor in MOTION_INPUTS.get(method, []):
                if not inputs:
                    inputs = ["--config", sequence / "sensors.yaml"]
                inputs += (["--imu", sequence / "imu.csv"] if sensor == "imu"
                           else ["--wheel-odom", sequence / "wheel_odom.csv"])
            # Logs beside the run's folder, named after it whole (a method may hold a dot).
            self.run([self.bin / "run_sequence", "--config", config] + inputs +
                     ["--input", sequence, "--output", out, "--cpu-time"] + self.methods[method],
                     out.parent / f"{out.name}.log")
            command = [self.bin / "evaluate_odometry", "--gt", gt or sequence / "poses.txt",
                       "--est", out / "poses_kitti.txt", "--json", out / "metrics.json"]
            if calib:
                command += ["--calib", calib]
            self.run(command, out.parent / f"{out.name}.eval.log")
        summary = json.loads((out / "summary.json").read_text())
        metrics = json.loads((out / "metrics.json").read_text())
        kitti = metrics.get("kitti") or {}
        drift = metrics.get("drift") or {}
        return {
            "t_err": kitti.get("t_err_percent"),
            "reach": drift.get("reach_ratio"),
            "along_track": drift.get("along_track_percent"),
            "cross_track": drift.get("cross_track_percent"),
            "motion_sensors": summary.get("motion_sensors"),
            "r_err": kitti.get("r_err_deg_per_100m"),
            "rpe": metrics["rpe"]["translation_rmse_m"],
            "ate": metrics["ate"]["rmse_m"],
            "fps": summary["frames_per_second"],
            "frame_ms": summary["frame_ms"],
            "frames": summary["frames"],
            "output": str(out),
        }

    def check_simulation_settings(self):
        """The work folder keeps its drives and runs for the next run: never mix two densities."""
        marker = self.work / "simulation.json"
        settings = {"foliage_density": self.foliage_density}
        if marker.exists():
            kept = json.loads(marker.read_text())
            if kept != settings:
                raise RuntimeError(f"{self.work} holds drives simulated with {kept}, not {settings}: "
                                   "give another --work or delete it")
        else:
            self.work.mkdir(parents=True, exist_ok=True)
            marker.write_text(json.dumps(settings) + "\n")

    def check_disk_space(self, drives):
        """Fails before simulating anything when the drives still to simulate would not fit."""
        missing = [(sensor, frames) for name, _, _, _, frames, sensor, seed in drives
                   if not (self.drive_folder(name, sensor, seed) / "poses.txt").exists()]
        needed = sum(DRIVE_BYTES_PER_SCAN[sensor] * frames for sensor, frames in missing)
        free = shutil.disk_usage(self.work).free
        if needed > free:
            raise RuntimeError(f"{len(missing)} drives to simulate need about {needed / 1e9:.1f} "
                               f"GB but {self.work} has {free / 1e9:.1f} GB free: free some space "
                               "there first")

    def simulated_suite(self, quick, seed_list=None, sensors=SENSORS):
        self.check_simulation_settings()
        drives = [(name, scenario, sequence, first, frames, sensor, seed)
                  for name, scenario, sequence, first, frames in scenarios(quick)
                  for sensor in sensors if sensor in SCENARIO_SENSORS.get(name, sensors)
                  for seed in seed_list or seeds(quick)]
        self.check_disk_space(drives)
        generate = []
        for drive in drives:
            name, *_, sensor, seed = drive
            generate.append((f"simulate {name} {sensor} seed {seed}",
                             lambda a=drive: (a, self.simulate(*a))))
        sequences = self.parallel(generate)
        runs = []
        for (name, _, sequence, first, frames, sensor, seed), folder in sequences:
            config = self.root / "config" / SENSORS[sensor]
            for method in self.methods:
                out = self.work / "runs" / folder.name / method.replace(" ", "")
                runs.append((f"{folder.name} {method}",
                             lambda k=(name, sensor, seed, method), f=folder, c=config, o=out:
                             (k, self.odometry(f, c, k[3], o))))
        results = []
        for (name, sensor, seed, method), figures in self.parallel(runs):
            figures.update(scenario=name, sensor=sensor, seed=seed, method=method)
            results.append(figures)
        return results

    def dead_reckoning(self, simulated):
        """The degenerate drives' dead-reckoning baselines (evaluate_odometry --baseline):
        constant velocity from the first second, and the simulated wheel odometry alone."""
        tasks = []
        for run in simulated:
            if run["scenario"] not in DEGENERATE or run["method"] != "adaptive":
                continue
            out = pathlib.Path(run["output"])
            sequence = self.drive_folder(run["scenario"], run["sensor"], run["seed"])
            config = self.root / "config" / SENSORS[run["sensor"]]
            for baseline, extra in (
                    ("constant-velocity", []),
                    ("wheel", [sequence / "wheel_odom.csv", "--config", config,
                               sequence / "sensors.yaml"])):
                result = out.parent / f"{out.name}.baseline_{baseline}.json"
                command = [self.bin / "evaluate_odometry", "--gt", sequence / "poses.txt",
                           "--est", out / "poses_kitti.txt", "--times", sequence / "times.txt",
                           "--json", result, "--baseline", baseline] + extra
                tasks.append((f"baseline {baseline} {out.parent.name}",
                              lambda c=command, r=result, k=run, b=baseline:
                              (k, b, self.run_json(c, r))))
        rows = []
        for run, baseline, metrics in self.parallel(tasks):
            rows.append({"scenario": run["scenario"], "sensor": run["sensor"],
                         "seed": run["seed"], "baseline": baseline,
                         "drift": metrics["baseline"]["drift"]})
        return rows

    def degeneration_scores(self, simulated):
        """The degenerate flag and the published covariance of the adaptive runs, LiDAR alone
        and with both motion sensors, against each drive's true observability (evaluate_odometry
        --observability --degeneration), from the runs' outputs as they are."""
        tasks = []
        for run in simulated:
            if run["method"] not in DEGENERATION_METHODS:
                continue
            out = pathlib.Path(run["output"])
            sequence = self.drive_folder(run["scenario"], run["sensor"], run["seed"])
            result = out.parent / f"{out.name}.degeneration.json"
            command = [self.bin / "evaluate_odometry", "--gt", sequence / "poses.txt",
                       "--est", out / "poses_kitti.txt", "--observability",
                       sequence / "observability.csv", "--degeneration",
                       out / "degeneration.csv", "--config",
                       self.root / "config" / SENSORS[run["sensor"]], "--json", result]
            tasks.append((f"degeneration {out.parent.name} {run['method']}",
                          lambda c=command, r=result, k=run: (k, self.run_json(c, r))))
        rows = []
        for run, metrics in self.parallel(tasks):
            rows.append({key: run[key] for key in ("scenario", "sensor", "seed", "method")} |
                        {"degeneration": metrics["degeneration"]})
        return rows

    # -- real KITTI ------------------------------------------------------------------------

    def real_kitti(self):
        kitti = self.data / "kitti_odometry"
        sequences = [("07 (frames 0-4)", kitti / "seq07_frames0-4", "poses.txt")]
        for number in ["00", "02", "05", "08"]:
            sequences.append((f"{number} (first 10)", kitti / "first10" / number,
                              "semantickitti_poses.txt"))
        runs = []
        for label, folder, gt in sequences:
            for method in LIDAR_METHODS:  # the real scans come without motion sensors
                out = self.work / "real" / folder.name / method.replace(" ", "")
                runs.append((f"KITTI {label} {method}",
                             lambda l=label, f=folder, g=gt, m=method, o=out:
                             (l, m, self.odometry(f, self.root / "config" / "kitti.yaml", m, o,
                                                  f / g, f / "calib.txt"))))
        results = []
        for label, method, figures in self.parallel(runs):
            figures.update(sequence=label, method=method)
            results.append(figures)
        return results

    # -- clustering benchmark (Table I) -----------------------------------------------------

    def clustering(self, quick):
        bench = self.data / "clustering_bench"
        settings = [("distance", 3), ("range_difference", 3), ("range_difference", 5)]
        if quick:
            settings = settings[:2]
        runs = []
        for criterion, window in settings:
            out = self.work / "clustering" / f"{criterion}_w{window}.json"
            command = [self.bin / "segmentation_bench", "--points", bench / "points_noground",
                       "--labels", bench / "labels", "--method", "all", "--criterion", criterion,
                       "--window", window, "--json", out]
            runs.append((f"clustering benchmark, {criterion}, w {window}",
                         lambda c=command, o=out, k=(criterion, window):
                         (k, self.run_json(c, o))))
        return [{"criterion": k[0], "window": k[1], "result": r} for k, r in self.parallel(runs)]

    def run_json(self, command, out):
        if not out.exists():
            out.parent.mkdir(parents=True, exist_ok=True)
            self.run(command, out.with_suffix(".log"))
        return json.loads(out.read_text())

    # -- what each threshold drops, per class (looking at the clouds) -----------------------

    def point_flags(self, quick):
        """segment_scans --point-flags on every 10th scan of seed 1 of the two scenes the paper
        discriminates, per threshold: which points each keeps and drops."""
        runs = []
        for scenario in ["green_highway", "busy_street"]:
            for sensor, config in SENSORS.items():
                sequence = self.work / "sequences" / f"{scenario}_{sensor}_s1"
                files = sorted((sequence / "velodyne").glob("*.bin"))[::10]
                for setting in ["10", "30", "60", "adaptive"]:
                    out = self.work / "flags" / f"{scenario}_{sensor}" / setting
                    threshold = ["--adaptive"] if setting == "adaptive" else ["--beta0", setting]
                    command = ([self.bin / "segment_scans", "--config", self.root / "config" / config]
                               + threshold + ["--point-flags", out] + files)
                    runs.append((f"point flags {scenario} {sensor} {setting}",
                                 lambda c=command, o=out: self.run_once(c, o)))
        self.parallel(runs)
        return str(self.work / "flags")

    def run_once(self, command, out):
        if not (out / "done").exists():
            self.run(command, out.parent / f"{out.name}.log")
            (out / "done").write_text("")

    # -- mu from the range image and from a KD-tree (Fig. 8) --------------------------------

    def degeneration(self, quick):
        folder = self.work / "sequences" / "green_highway_hdl64e_s1" / "velodyne"
        files = sorted(folder.glob("*.bin"))[::20 if quick else 10]
        out = self.work / "fig8_degeneration.txt"
        if not out.exists():
            self.run([self.bin / "segment_scans", "--config", self.root / "config" / "kitti.yaml",
                      "--degeneration"] + files, out)
        rows = []
        for line in out.read_text().splitlines()[1:]:
            fields = line.split()
            rows.append({"frame": int(pathlib.Path(fields[0]).stem), "mu": float(fields[1]),
                         "image_ms": float(fields[4]), "mu_kdtree": float(fields[5]),
                         "kdtree_ms": float(fields[7])})
        return rows


def add_runner_arguments(parser):
    """The folders and the parallelism a Runner needs (suite.py, tune_beta0_map.py)."""
    for folder in ("--bin", "--root", "--data", "--work"):
        parser.add_argument(folder, required=True)
    parser.add_argument("--jobs", type=int, default=2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_runner_arguments(parser)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--foliage-density", type=float,
                        help="lidar_sim --foliage-density for every simulated drive")
    args = parser.parse_args()
    runner = Runner(args)
    started = time.time()
    results = {"quick": args.quick, "methods": list(METHODS),
               "foliage_density": args.foliage_density}
    try:
        results["simulated"] = runner.simulated_suite(args.quick)
        results["dead_reckoning"] = runner.dead_reckoning(results["simulated"])
        results["degeneration_scores"] = runner.degeneration_scores(results["simulated"])
        results["real"] = runner.real_kitti()
        results["clustering"] = runner.clustering(args.quick)
        results["degeneration"] = runner.degeneration(args.quick)
        results["flags"] = runner.point_flags(args.quick)
    except RuntimeError as error:
        sys.stderr.write(f"\nexperiments: {error}\n")
        return 1
    results["minutes"] = (time.time() - started) / 60.0
    results["machine"] = f"{os.cpu_count()} cores, {os.uname().sysname} {os.uname().release}"
    (pathlib.Path(args.work) / "results.json").write_text(json.dumps(results, indent=1))
    sys.stderr.write(f"\nexperiments: done in {results['minutes']:.1f} min\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
