#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the embedded default data: the whole
# pipeline (ambient filter, odometry, mapping) over the real KITTI sequence 07 scans in test/data,
# then the evaluation of its poses against KITTI's ground truth.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

sequence="$ALEGO_ROOT/test/data/kitti_seq07"
output="$ALEGO_WS/demo_output"
"$ALEGO_BIN/run_sequence" --config "$ALEGO_ROOT/config/kitti.yaml" --input "$sequence" \
  --output "$output"
echo
echo "Per frame (ms) and the ambient filter's output:"
paste -d, "$output/timing.csv" "$output/degeneration.csv" | awk -F, '
  NR == 1 {
    for (i = 1; i <= NF; ++i) if (!($i in col)) col[$i] = i  # first: timing.csv
    printf "%6s %8s %8s %8s %8s %8s %6s %9s %9s\n", "frame", "filter", "features", "odometry",
           "mapping", "total", "mu", "beta0_deg", "skeleton"
    next
  }
  {
    filter = $col["projection"] + $col["ground"] + $col["euclidean_clustering"]
    filter += $col["skeleton"] + $col["normals"] + $col["degeneration"]
    filter += $col["depth_clustering"] + $col["segmented_cloud"]
    mapping = $col["mapping"] + $col["local_map"]
    printf "%6d %8.1f %8.1f %8.1f %8.1f %8.1f %6.3f %9.1f %9d\n", $1, filter, $col["features"],
           $col["odometry"], mapping, $col["total"], $col["mu"], $col["beta0_deg"],
           $col["skeleton_points"]
  }'
echo
echo "Against KITTI's ground truth:"
"$ALEGO_BIN/evaluate_odometry" --gt "$sequence/poses.txt" --est "$output/poses_kitti.txt" \
  --calib "$sequence/calib.txt"
echo "Outputs: $output"
