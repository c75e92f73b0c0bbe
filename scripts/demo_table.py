#!/usr/bin/env python3
"""Prints the demo's table: for each sequence folder of the demo's output and each run in it
(adaptive, fixed60), KITTI t_err, the per-scan error, mean mu ('-': not computed, as in
fixed mode) and frames per second.

    demo_table.py DEMO_OUT SEQUENCE [SEQUENCE ...]

Reads SEQUENCE/<run>/metrics.json (evaluate_odometry --json), summary.json and degeneration.csv.
"""

import argparse
import csv
import json
import pathlib
import sys

RUNS = [("adaptive", "adaptive"), ("fixed60", "fixed 60 deg")]


def fail(message):
    print(f"demo_table: {message}", file=sys.stderr)
    sys.exit(1)


def read_json(path):
    try:
        return json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as error:
        fail(f"{path}: {error}")


def mean_mu(path):
    try:
        with path.open() as file:
            rows = [row for row in csv.DictReader(file) if row.get("valid", "1") == "1"]
        values = [float(row["mu"]) for row in rows]
    except (OSError, KeyError, ValueError) as error:
        fail(f"{path}: expected a column mu of numbers ({error})")
    return sum(values) / len(values) if values else None


def format_mu(mu):
    return "-" if mu is None else f"{mu:.2f}"


def row(sequence, run_dir, label):
    metrics = read_json(run_dir / "metrics.json")
    summary = read_json(run_dir / "summary.json")
    t_err = metrics.get("kitti", {}).get("t_err_percent")
    rpe = metrics.get("rpe", {}).get("translation_rmse_m")
    return (f"{sequence:<11} {label:<13} "
            f"{'n/a (< 100 m)' if t_err is None else f'{t_err:.2f}':>13} "
            f"{'n/a' if rpe is None else f'{100 * rpe:.1f}':>12} "
            f"{format_mu(mean_mu(run_dir / 'degeneration.csv')):>8} "
            f"{summary.get('frames_per_second', float('nan')):>9.1f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("demo_out", type=pathlib.Path)
    parser.add_argument("sequences", nargs="+")
    args = parser.parse_args()
    print(f"{'sequence':<11} {'beta0':<13} {'t_err %':>13} {'RPE cm/scan':>12} "
          f"{'mean mu':>8} {'frames/s':>9}")
    for sequence in args.sequences:
        for run_name, label in RUNS:
            print(row(sequence, args.demo_out / sequence / run_name, label))


if __name__ == "__main__":
    main()
