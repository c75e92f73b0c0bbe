#!/usr/bin/env python3
"""Measure an HDL-64E beam table (elevation and vertical origin offset per beam) from KITTI scans.

KITTI's .bin files keep the sensor's firing order: each laser's sweep follows the previous one,
so unwrapping the azimuth along the file and counting whole turns gives each point's laser.
A line z = h + tan(theta) * r_xy fitted to each laser's points gives its elevation theta and the
height h of its origin above the sensor origin. Prints the `beam_angles_deg` and
`beam_offsets_m` lists of config/kitti.yaml (row 0 = lowest beam).

usage: /usr/bin/python3 scripts/fit_beam_table.py SCAN.bin [SCAN.bin ...]
"""
import sys

import numpy as np


def laser_index(points):
    azimuth = np.unwrap(np.arctan2(points[:, 1], points[:, 0]))
    return np.floor((azimuth - azimuth[0]) / (2 * np.pi) + 1e-3).astype(int)


def main(paths):
    fits = []
    for path in paths:
        points = np.fromfile(path, dtype=np.float32).reshape(-1, 4)
        laser = laser_index(points)
        horizontal = np.hypot(points[:, 0], points[:, 1])
        if laser.max() + 1 != 64:
            sys.exit(f"{path}: found {laser.max() + 1} laser sweeps, expected 64")
        per_scan = []
        for k in range(64):
            mask = (laser == k) & (horizontal > 2.0)
            design = np.c_[np.ones(mask.sum()), horizontal[mask]]
            offset, slope = np.linalg.lstsq(design, points[mask, 2], rcond=None)[0]
            per_scan.append((np.degrees(np.arctan(slope)), offset))
        fits.append(per_scan)
    table = np.mean(np.array(fits), axis=0)[::-1]  # the file starts with the top laser
    print("  beam_angles_deg: [" + ", ".join(f"{a:.3f}" for a in table[:, 0]) + "]")
    print("  beam_offsets_m: [" + ", ".join(f"{h:.4f}" for h in table[:, 1]) + "]")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
