#!/usr/bin/env python3
"""How much each class of points changes from one scan to the next, real KITTI against simulated
scans, and what a fixed depth-clustering threshold drops of it.

For each pair of consecutive scans, the second is aligned onto the first by point-to-plane ICP on
the static classes alone (road, sidewalk, parking, building, fence, other structure, pole, sign,
trunk, terrain), starting from the sequence's poses; a point's residual is its distance to the
nearest point of the aligned next scan. Printed per class, over the points 5-30 m away: the median
residual and the share beyond 10 cm; then, for beta0 fixed at 10, 30 and 60 deg
(`segment_scans --point-flags`), the share of the non-ground points dropped and the residuals of
those kept and those dropped.

  /usr/bin/python3 scripts/experiments/scan_residuals.py --bin .ws/devel/lib/adaptive_lego_loam \
      --data DATA --work results/scan_residuals [--foliage-density X]

DATA holds kitti_odometry/first10/{00,02,05,08} (scans with SemanticKITTI labels) and
kitti_odometry/poses/00.txt; the simulated drives are made in --work by lidar_sim.
"""
import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

try:
    from scipy.spatial import cKDTree
except ImportError:
    sys.exit("scan_residuals: needs scipy (Debian: apt-get install python3-scipy)")

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from plot_run import InputError, load_ground_truth  # noqa: E402  (scripts/ is not a package)

STATIC = [40, 44, 48, 49, 50, 51, 52, 71, 72, 80, 81]
CLASSES = {"building, fence": [50, 51, 52], "trunk, pole, sign": [71, 80, 81], "car": [10, 252],
           "vegetation": [70]}
THRESHOLDS_DEG = (10, 30, 60)
PAIRS = 9


def read_scan(sequence, frame):
    points = np.fromfile(sequence / "velodyne" / f"{frame:06d}.bin", np.float32).reshape(-1, 4)
    labels = np.fromfile(sequence / "labels" / f"{frame:06d}.label", np.uint32) & 0xFFFF
    return points[:, :3].astype(float), labels


def plane_normals(points, tree, k=8):
    _, neighbours = tree.query(points, k)
    centred = points[neighbours] - points[neighbours].mean(axis=1, keepdims=True)
    _, vectors = np.linalg.eigh(np.einsum("nki,nkj->nij", centred, centred))
    return vectors[:, :, 0]


def rotation(rotation_vector):
    angle = np.linalg.norm(rotation_vector)
    x, y, z = rotation_vector
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    if angle < 1e-12:
        return np.eye(3) + k
    return np.eye(3) + np.sin(angle) / angle * k + (1 - np.cos(angle)) / angle**2 * k @ k


def align(source, target, guess, iterations=30):
    """Point-to-plane ICP with a Huber weight (10 cm); returns source -> target."""
    tree = cKDTree(target)
    normals = plane_normals(target, tree)
    transform = guess.copy()
    for _ in range(iterations):
        moved = source @ transform[:3, :3].T + transform[:3, 3]
        distance, index = tree.query(moved, 1, distance_upper_bound=1.0)
        found = np.isfinite(distance)
        moved, nearest, normal = moved[found], target[index[found]], normals[index[found]]
        residual = np.einsum("ni,ni->n", moved - nearest, normal)
        jacobian = np.hstack([np.cross(moved, normal), normal])
        weight = 1.0 / np.maximum(1.0, np.abs(residual) / 0.1)
        step = np.linalg.solve(jacobian.T @ (jacobian * weight[:, None]),
                               -jacobian.T @ (residual * weight))
        update = np.eye(4)
        update[:3, :3], update[:3, 3] = rotation(step[:3]), step[3:]
        transform = update @ transform
        if np.linalg.norm(step) < 1e-6:
            break
    return transform


def point_flags(binaries, config, sequence, work):
    """Per threshold and frame: 0 not projected, 1 ground, 2 kept, 3 dropped."""
    flags = {}
    for beta0 in THRESHOLDS_DEG:
        folder = work / "flags" / sequence.name / str(beta0)
        folder.mkdir(parents=True, exist_ok=True)
        subprocess.run([str(binaries / "segment_scans"), "--config", str(config), "--beta0",
                        str(beta0), "--point-flags", str(folder), str(sequence / "velodyne")],
                       check=True, stdout=subprocess.DEVNULL)
        flags[beta0] = folder
    return flags


def measure(binaries, config, sequence, pose_file, work):
    poses = load_ground_truth(str(pose_file), str(sequence / "calib.txt"))
    flag_folders = point_flags(binaries, config, sequence, work)
    residuals, labels, flags = [], [], {beta0: [] for beta0 in THRESHOLDS_DEG}
    for frame in range(PAIRS):
        points, frame_labels = read_scan(sequence, frame)
        following, following_labels = read_scan(sequence, frame + 1)
        guess = np.linalg.inv(poses[frame]) @ poses[frame + 1]
        transform = align(following[np.isin(following_labels, STATIC)],
                          points[np.isin(frame_labels, STATIC)], guess)
        tree = cKDTree(following @ transform[:3, :3].T + transform[:3, 3])
        ranges = np.linalg.norm(points, axis=1)
        near = (ranges >= 5) & (ranges < 30)
        residuals.append(tree.query(points[near], 1)[0])
        labels.append(frame_labels[near])
        for beta0, folder in flag_folders.items():
            flags[beta0].append(np.fromfile(folder / f"{frame:06d}.flags", np.uint8)[near])
    return (np.concatenate(residuals), np.concatenate(labels),
            {beta0: np.concatenate(parts) for beta0, parts in flags.items()})


def spread(values):
    if len(values) == 0:
        return "-"
    return f"{100 * np.median(values):.1f} cm, {100 * np.mean(values > 0.1):.0f} %"


def report(name, residuals, labels, flags):
    print(f"{name}")
    for group, ids in CLASSES.items():
        of_group = np.isin(labels, ids)
        if of_group.sum() < 300:
            continue
        line = f"  {group:17s} {of_group.sum():7d} points, residual {spread(residuals[of_group])}"
        for beta0 in THRESHOLDS_DEG:
            segmented = of_group & ((flags[beta0] == 2) | (flags[beta0] == 3))
            dropped = segmented & (flags[beta0] == 3)
            kept = segmented & (flags[beta0] == 2)
            share = 100 * dropped.sum() / max(segmented.sum(), 1)
            line += (f" | {beta0} deg: drops {share:.0f} %, kept {spread(residuals[kept])},"
                     f" dropped {spread(residuals[dropped])}")
        print(line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", required=True, type=Path, help="folder with lidar_sim, segment_scans")
    parser.add_argument("--data", required=True, type=Path, help="folder with kitti_odometry/")
    parser.add_argument("--work", required=True, type=Path, help="folder for the simulated drives")
    parser.add_argument("--foliage-density", type=float,
                        help="lidar_sim --foliage-density of the simulated drives (default: its own)")
    parser.add_argument("--config", type=Path,
                        default=Path(__file__).resolve().parents[2] / "config" / "kitti.yaml")
    args = parser.parse_args()
    kitti = args.data / "kitti_odometry"
    first10 = kitti / "first10"
    if not first10.is_dir():
        sys.exit(f"scan_residuals: {first10}: no such folder (the first 10 scans of KITTI 00, 02, "
                 "05, 08 with SemanticKITTI labels)")
    args.work.mkdir(parents=True, exist_ok=True)
    print("residual: median distance to the next scan, share beyond 10 cm (points 5-30 m away)")
    for number in ("00", "02", "05", "08"):
        sequence = first10 / number
        # SemanticKITTI's poses: KITTI's own are off by up to 1.5 m over these ten scans.
        report(f"real KITTI {number}",
               *measure(args.bin, args.config, sequence, sequence / "semantickitti_poses.txt",
                        args.work))
    density = [] if args.foliage_density is None else ["--foliage-density", f"{args.foliage_density:g}"]
    drives = {"urban": ["--trajectory", str(kitti / "poses" / "00.txt"), "--seed", "21"],
              "busy_street": ["--seed", "1"], "vegetation": ["--seed", "1"]}
    for scenario, options in drives.items():
        sequence = args.work / scenario
        subprocess.run([str(args.bin / "lidar_sim"), "--scenario", scenario, "--sensor", "hdl64e",
                        "--frames", str(PAIRS + 1), "--output", str(sequence), "--overwrite",
                        *options, *density], check=True, stdout=subprocess.DEVNULL)
        report(f"simulated {scenario} ({' '.join(options + density).replace(str(kitti) + '/', '')})",
               *measure(args.bin, args.config, sequence, sequence / "poses.txt", args.work))


if __name__ == "__main__":
    try:
        main()
    except InputError as error:
        sys.exit(f"scan_residuals: {error}")
