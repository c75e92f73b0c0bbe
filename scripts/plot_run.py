#!/usr/bin/env python3
"""Plots one or more output folders of run_sequence: the top view of the trajectory, the
degeneration degree mu and the depth-clustering threshold beta0 per scan, the per-scan
translational error against a KITTI ground truth and the processing time per scan.

Several folders are overlaid in the same figures, e.g. the adaptive filter against a fixed
beta0 on the same input:

    scripts/plot_run.py out/adaptive out/fixed60 --label adaptive "fixed 60 deg" \\
        --gt sequence/poses.txt --calib sequence/calib.txt --output plots --title "seq 07"

--gt takes a KITTI pose file (a row-major 3x4 [R|t] per line); --calib a KITTI calib.txt whose
Tr: line maps the camera-frame ground truth to the lidar frame (Tr^-1 * P * Tr). Without
--calib the ground truth is taken to be in the lidar frame already.

Writes trajectory.png, mu_beta0.png, timing.png and, with --gt, per_scan_error.png to --output
(default: the first folder) and prints the path of each. Bad input exits with 1 and one line on
stderr starting with "plot_run: "; usage errors exit with 2. Needs Python 3, numpy, matplotlib.
"""

import argparse
import csv
import dataclasses
import json
import math
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.ticker import MaxNLocator  # noqa: E402

FIGURE_WIDTH_IN = 12.0
DPI = 110
FEW_FRAMES = 50  # runs with fewer frames also get a marker per frame
LOG_SCALE_SPREAD = 30.0  # per-scan error axis turns logarithmic past this max / median ratio
ROTATION_TOLERANCE = 1e-2
BETA0_MIN_SPAN_DEG = 10.0  # the beta0 axis spans at least this much
POSE_EXPECTED = "12 numbers (a row-major 3x4 [R|t] pose)"
DEGENERATION_COLUMNS = ["frame", "mu", "beta0_deg", "valid"]
TIMING_COLUMNS = ["frame", "total"]
FONTS = {"font.size": 12, "axes.titlesize": 14, "axes.labelsize": 13, "legend.fontsize": 11,
         "xtick.labelsize": 11, "ytick.labelsize": 11}


class InputError(Exception):
    """Bad input; the message names the file, the line or field and what was expected."""


@dataclasses.dataclass
class Run:
    """One run_sequence output folder."""
    label: str
    poses: np.ndarray  # (frames, 4, 4) lidar poses, the first one identity
    degeneration: dict  # DEGENERATION_COLUMNS -> per-row arrays
    timing: dict  # TIMING_COLUMNS -> per-row arrays


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Plots run_sequence output folders (overlaid when several).")
    parser.add_argument("out_dirs", nargs="+", metavar="OUT_DIR",
                        help="a run_sequence output folder")
    parser.add_argument("--label", nargs="+", action="extend", metavar="NAME",
                        help="legend name of each OUT_DIR, one per folder "
                             "(default: the folder's name and beta0 mode)")
    parser.add_argument("--gt", metavar="POSES", help="KITTI ground-truth pose file")
    parser.add_argument("--calib", metavar="CALIB",
                        help="KITTI calib.txt whose Tr: line maps the ground truth to the lidar "
                             "frame (default: the ground truth is in the lidar frame)")
    parser.add_argument("--output", metavar="DIR",
                        help="folder for the PNGs (default: the first OUT_DIR)")
    parser.add_argument("--title", default="", metavar="TEXT", help="prefix of figure titles")
    args = parser.parse_args(argv)
    if args.label is not None and len(args.label) != len(args.out_dirs):
        parser.error(f"--label gives {len(args.label)} name(s) for {len(args.out_dirs)} "
                     f"folder(s): give one per OUT_DIR")
    if args.calib and not args.gt:
        parser.error("--calib needs --gt")
    return args


def shown(field):
    """A field of the input as it goes into a one-line message."""
    text = field.strip()
    return repr(text if len(text) <= 40 else text[:37] + "...")


def read_text(path, expected):
    try:
        with open(path, encoding="utf-8") as stream:
            text = stream.read()
    except FileNotFoundError:
        raise InputError(f"{path}: no such file, expected {expected}") from None
    except OSError as error:
        raise InputError(f"{path}: cannot read it ({error.strerror}), "
                         f"expected {expected}") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text file, expected {expected}") from None
    if not text.strip():
        raise InputError(f"{path}: empty file, expected {expected}")
    return text


def parse_number(field, where, expected):
    try:
        return float(field)
    except ValueError:
        raise InputError(f"{where}: expected {expected}, got {shown(field)}") from None


def parse_pose(fields, where):
    """A 4x4 homogeneous matrix from the 12 numbers of a row-major 3x4 [R|t]."""
    if len(fields) != 12:
        raise InputError(f"{where}: expected {POSE_EXPECTED}, got {len(fields)} field(s)")
    values = [parse_number(field, where, POSE_EXPECTED) for field in fields]
    if not all(math.isfinite(value) for value in values):
        raise InputError(f"{where}: expected {POSE_EXPECTED}, got a non-finite number")
    pose = np.eye(4)
    pose[:3, :] = np.reshape(values, (3, 4))
    rotation = pose[:3, :3]
    if np.abs(rotation.T @ rotation - np.eye(3)).max() > ROTATION_TOLERANCE:
        raise InputError(f"{where}: expected a rotation in the first 3x3 of the pose, got a "
                         f"matrix that is not orthonormal")
    return pose


def read_poses(path):
    """Reads a KITTI pose file: one row-major 3x4 [R|t] per line. Returns (N, 4, 4) poses."""
    lines = read_text(path, "one 3x4 pose (12 numbers) per line").rstrip().splitlines()
    return np.array([parse_pose(line.split(), f"{path}:{number}")
                     for number, line in enumerate(lines, 1)])


def read_calib_tr(path):
    """Reads the velodyne-to-camera transform Tr of a KITTI calib.txt as a 4x4 matrix."""
    text = read_text(path, "a KITTI calib.txt with a 'Tr:' line")
    for number, line in enumerate(text.splitlines(), 1):
        key, colon, rest = line.partition(":")
        if colon and key.strip() in ("Tr", "Tr_velo_to_cam"):
            return parse_pose(rest.split(), f"{path}:{number}")
    raise InputError(f"{path}: no 'Tr:' line, expected the 12 numbers of the velodyne-to-camera "
                     f"transform")


def read_csv_columns(path, columns):
    """Reads the named columns of a CSV file with a header line into float arrays."""
    rows = list(csv.reader(read_text(path, "a CSV file with a header line").splitlines()))
    header = [name.strip() for name in rows[0]]
    for name in columns:
        if name not in header:
            raise InputError(f"{path}:1: no column '{name}' in the header, expected the "
                             f"columns {','.join(columns)}")
    indices = {name: header.index(name) for name in columns}
    values = {name: [] for name in columns}
    for number, row in enumerate(rows[1:], 2):
        if not row:
            continue
        if len(row) != len(header):
            raise InputError(f"{path}:{number}: expected {len(header)} fields as in the header, "
                             f"got {len(row)}")
        for name, index in indices.items():
            values[name].append(parse_number(row[index], f"{path}:{number}: column {name}",
                                             "a number"))
    if not values[columns[0]]:
        raise InputError(f"{path}: no data row after the header, expected one row per scan")
    return {name: np.array(column) for name, column in values.items()}


def beta0_mode(folder):
    """The beta0_mode of the folder's summary.json, or None without one."""
    path = os.path.join(folder, "summary.json")
    if not os.path.exists(path):
        return None
    try:
        summary = json.loads(read_text(path, "the run summary (JSON)"))
    except json.JSONDecodeError as error:
        raise InputError(f"{path}:{error.lineno}: expected the run summary as JSON "
                         f"({error.msg})") from None
    mode = summary.get("beta0_mode") if isinstance(summary, dict) else None
    return mode if isinstance(mode, str) else None


def default_label(folder):
    name = os.path.basename(os.path.normpath(folder))
    mode = beta0_mode(folder)
    return f"{name} ({mode})" if mode else name


def load_run(folder, label):
    if not os.path.isdir(folder):
        raise InputError(f"{folder}: no such folder, expected a run_sequence output folder")
    return Run(label=label if label is not None else default_label(folder),
               poses=read_poses(os.path.join(folder, "poses_kitti.txt")),
               degeneration=read_csv_columns(os.path.join(folder, "degeneration.csv"),
                                             DEGENERATION_COLUMNS),
               timing=read_csv_columns(os.path.join(folder, "timing.csv"), TIMING_COLUMNS))


def load_ground_truth(poses_path, calib_path):
    """The ground truth in the lidar frame, each pose relative to the first one."""
    poses = read_poses(poses_path)
    if calib_path:
        velodyne_to_camera = read_calib_tr(calib_path)
        poses = np.linalg.inv(velodyne_to_camera) @ poses @ velodyne_to_camera
    return np.linalg.inv(poses[0]) @ poses


def per_scan_errors_cm(estimate, truth):
    """|translation of (Q_{i-1}^-1 Q_i)^-1 (P_{i-1}^-1 P_i)| in cm for frames i >= 1."""
    estimated_steps = np.linalg.inv(estimate[:-1]) @ estimate[1:]
    true_steps = np.linalg.inv(truth[:-1]) @ truth[1:]
    errors = np.linalg.inv(true_steps) @ estimated_steps
    return 100.0 * np.linalg.norm(errors[:, :3, 3], axis=1)


def common_frames(run, truth):
    """How many frames the run and the ground truth share; warns when their lengths differ."""
    count = min(len(run.poses), len(truth))
    if len(run.poses) != len(truth):
        print(f"plot_run: warning: {run.label} has {len(run.poses)} poses, the ground truth "
              f"{len(truth)}: comparing the first {count}", file=sys.stderr)
    return count


def format_value(value):
    if value < 10:
        return f"{value:.2f}"
    return f"{value:.1f}" if value < 1000 else f"{value:.0f}"


def titled(prefix, text):
    return f"{prefix}: {text}" if prefix else text


def frame_marker(count):
    return "o" if count < FEW_FRAMES else None


def new_figure(height_in, rows=1):
    figure, axes = plt.subplots(rows, 1, sharex=True, squeeze=False,
                                figsize=(FIGURE_WIDTH_IN, height_in), dpi=DPI)
    for panel in axes[:, 0]:
        panel.grid(True, color="0.85", linewidth=0.8)
    return figure, list(axes[:, 0])


def frame_axis(axes):
    axes.set_xlabel("frame")
    axes.xaxis.set_major_locator(MaxNLocator(integer=True, steps=[1, 2, 2.5, 5, 10]))


def add_note(axes, text):
    axes.text(0.01, 0.01, text, transform=axes.transAxes, fontsize=10, color="0.3",
              ha="left", va="bottom", bbox={"facecolor": "white", "edgecolor": "0.8",
                                            "alpha": 0.9})


def save_figure(figure, directory, name):
    """Writes the figure to a temporary file in directory, then renames it to name."""
    path = os.path.join(directory, name)
    temporary = os.path.join(directory, f".{name}.{os.getpid()}.tmp")
    try:
        figure.tight_layout()
        figure.savefig(temporary, format="png", dpi=DPI)
        os.replace(temporary, path)
    except OSError as error:
        raise InputError(f"{path}: cannot write it ({error.strerror})") from None
    finally:
        plt.close(figure)
        if os.path.exists(temporary):
            os.remove(temporary)
    print(path, flush=True)
    return path


def ground_truth_view(truth):
    """The x-y box of the ground truth with a margin, as (low corner, high corner, margin)."""
    low, high = truth[:, :2, 3].min(axis=0), truth[:, :2, 3].max(axis=0)
    margin = max(0.25 * float((high - low).max()), 10.0)
    return low - margin, high + margin, margin


def runs_off_view(runs, truth, low, high):
    """Labels of the runs that leave the box while the ground truth lasts (a lost run)."""
    inside = [run.poses[:len(truth), :2, 3] for run in runs]
    return [run.label for run, track in zip(runs, inside)
            if (track < low).any() or (track > high).any()]


def trajectory_view(runs, truth):
    """The x-y box to show and a note when it cuts off a run that wandered off the truth."""
    tracks = [run.poses[:, :2, 3] for run in runs] + ([] if truth is None else [truth[:, :2, 3]])
    points = np.concatenate(tracks)
    if truth is not None:
        low, high, margin = ground_truth_view(truth)
        off_view = runs_off_view(runs, truth, low, high)
        if off_view:
            return low, high, (f"view limited to the ground truth \u00b1 {margin:.0f} m; "
                               f"leaving it: {', '.join(off_view)}")
    return points.min(axis=0), points.max(axis=0), None


def trajectory_height(low, high):
    aspect = float((high[1] - low[1]) / max(high[0] - low[0], 1e-6))
    return min(max(FIGURE_WIDTH_IN * aspect * 0.9, 6.0), 12.0)


def plot_trajectory(runs, truth, title, directory):
    low, high, clipped_note = trajectory_view(runs, truth)
    figure, (axes,) = new_figure(trajectory_height(low, high))
    if truth is not None:
        axes.plot(truth[:, 0, 3], truth[:, 1, 3], color="black", linewidth=2.4,
                  label="ground truth", zorder=2)
    for index, run in enumerate(runs):
        axes.plot(run.poses[:, 0, 3], run.poses[:, 1, 3], color=f"C{index}", linewidth=1.6,
                  marker=frame_marker(len(run.poses)), markersize=4, label=run.label, zorder=3)
    start = runs[0].poses[0, :2, 3]
    axes.plot(start[0], start[1], linestyle="none", marker="*", markersize=18, color="gold",
              markeredgecolor="black", label="start", zorder=4)
    axes.set_aspect("equal", adjustable="datalim")
    if clipped_note:
        axes.set_xlim(low[0], high[0])
        axes.set_ylim(low[1], high[1])
        add_note(axes, clipped_note)
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    axes.set_title(titled(title, "trajectory, top view (lidar frame)"))
    axes.legend(loc="best", framealpha=0.9)
    return save_figure(figure, directory, "trajectory.png")


def widen_to(axes, span):
    """Widens the y range of axes to at least span, so that small wiggles look small."""
    low, high = axes.get_ylim()
    if high - low < span:
        middle = 0.5 * (low + high)
        axes.set_ylim(middle - 0.5 * span, middle + 0.5 * span)


def unknown_mu_row(index):
    """The height below mu = 0 at which run index marks its scans with unknown mu."""
    return -0.06 - 0.05 * index


def plot_mu_beta0(runs, title, directory):
    figure, (mu_axes, beta0_axes) = new_figure(8.5, rows=2)
    for index, run in enumerate(runs):
        frames = run.degeneration["frame"]
        known = run.degeneration["valid"] != 0
        marker = frame_marker(len(frames))
        mu_axes.plot(frames, np.where(known, run.degeneration["mu"], np.nan), color=f"C{index}",
                     linewidth=1.3, marker=marker, markersize=4,
                     label=run.label if known.any() else None)
        if not known.all():
            unknown = frames[~known]
            mu_axes.plot(unknown, np.full(len(unknown), unknown_mu_row(index)), linestyle="none",
                         marker="|", markersize=7, color=f"C{index}",
                         label=f"{run.label}: mu unknown ({len(unknown)} scans)")
        beta0_axes.plot(frames, run.degeneration["beta0_deg"], color=f"C{index}", linewidth=1.3,
                        marker=marker, markersize=4, label=run.label)
    mu_axes.set_ylim(unknown_mu_row(len(runs) - 1) - 0.05, 1.05)
    mu_axes.set_yticks(np.linspace(0.0, 1.0, 6))
    mu_axes.set_ylabel("degeneration degree $\\mu$")
    mu_axes.set_title(titled(title, "degeneration degree and depth-clustering threshold"))
    mu_axes.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), framealpha=0.9)
    widen_to(beta0_axes, BETA0_MIN_SPAN_DEG)
    beta0_axes.set_ylabel("$\\beta_0$ (deg)")
    frame_axis(beta0_axes)
    beta0_axes.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), framealpha=0.9)
    return save_figure(figure, directory, "mu_beta0.png")


def needs_log_scale(errors_per_run):
    """Whether the largest error dwarfs the typical error of some run (outliers, a lost run)."""
    largest = max(float(errors.max()) for errors in errors_per_run)
    smallest_median = min(float(np.median(errors)) for errors in errors_per_run)
    return largest > LOG_SCALE_SPREAD * max(smallest_median, 1e-9)


def plot_per_scan_error(runs, truth, title, directory):
    figure, (axes,) = new_figure(6.5)
    all_errors = []
    for index, run in enumerate(runs):
        count = common_frames(run, truth)
        if count < 2:
            continue
        errors = per_scan_errors_cm(run.poses[:count], truth[:count])
        rmse = math.sqrt(float(np.mean(errors ** 2)))
        axes.plot(np.arange(1, count), errors, color=f"C{index}", linewidth=1.3,
                  marker=frame_marker(count), markersize=4,
                  label=f"{run.label}: RMSE {format_value(rmse)} cm")
        all_errors.append(errors)
    scale_note = ""
    if not all_errors:
        add_note(axes, "no run shares two frames with the ground truth")
    elif needs_log_scale(all_errors):
        axes.set_yscale("log")
        scale_note = ", log scale"
    if all_errors:
        axes.legend(loc="best", framealpha=0.9)
    frame_axis(axes)
    axes.set_ylabel(f"translational error (cm{scale_note})")
    axes.set_title(titled(title, "per-scan relative pose error against the ground truth"))
    return save_figure(figure, directory, "per_scan_error.png")


def plot_timing(runs, title, directory):
    figure, (axes,) = new_figure(6.5)
    for index, run in enumerate(runs):
        frames, total = run.timing["frame"], run.timing["total"]
        mean = float(np.nanmean(total)) if np.isfinite(total).any() else math.nan
        axes.plot(frames, total, color=f"C{index}", linewidth=1.1,
                  marker=frame_marker(len(frames)), markersize=4,
                  label=f"{run.label}: mean {format_value(mean)} ms")
    axes.set_ylim(bottom=0.0)
    frame_axis(axes)
    axes.set_ylabel("total time per scan (ms)")
    axes.set_title(titled(title, "processing time per scan"))
    axes.legend(loc="best", framealpha=0.9)
    return save_figure(figure, directory, "timing.png")


def output_directory(path):
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as error:
        raise InputError(f"{path}: cannot create the output folder ({error.strerror})") from None
    return path


def main(argv=None):
    args = parse_args(argv)
    labels = args.label or [None] * len(args.out_dirs)
    plt.rcParams.update(FONTS)
    try:
        runs = [load_run(folder, label) for folder, label in zip(args.out_dirs, labels)]
        truth = load_ground_truth(args.gt, args.calib) if args.gt else None
        directory = output_directory(args.output or args.out_dirs[0])
        plot_trajectory(runs, truth, args.title, directory)
        plot_mu_beta0(runs, args.title, directory)
        if truth is not None:
            plot_per_scan_error(runs, truth, args.title, directory)
        plot_timing(runs, args.title, directory)
    except InputError as error:
        print(f"plot_run: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
