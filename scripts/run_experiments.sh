#!/usr/bin/env bash
# Regenerates docs/RESULTS.md and its figures from nothing: builds, simulates every scenario (along
# real KITTI trajectories where they fit) with both sensors and 6 seeds, runs each with beta0
# fixed at 10, 30 and 60 deg, adaptive and without segmentation, runs the real KITTI scans and the
# clustering benchmark, then writes the page (scripts/experiments/). Two runs at a time.
#   scripts/run_experiments.sh [--quick] [--data DIR] [--jobs N] [--foliage-density X]
#     --quick   one seed, 100 scans, three scenarios (a few minutes)
#     --foliage-density  every simulated drive with lidar_sim --foliage-density X (outputs in
#               results/experiments_foliageX/)
#     --data    the folder with kitti_odometry/ (poses/, times/, seq07_frames0-4/, first10/) and
#               clustering_bench/; default $ALEGO_DATA
# Raw outputs go to results/experiments/ (git-ignored; kept between runs: delete it to start over).
# The full run's simulated scans take 48 GB there.
set -euo pipefail

quick=()
foliage=()
data="${ALEGO_DATA:-}"
jobs=2
while (($#)); do
  case "$1" in
    --quick) quick=(--quick) ;;
    --data)
      data="${2:?--data needs a folder}"
      shift
      ;;
    --jobs)
      jobs="${2:?--jobs needs a number}"
      shift
      ;;
    --foliage-density)
      foliage=(--foliage-density "${2:?--foliage-density needs a number}")
      shift
      ;;
    -h | --help)
      sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"
      exit 0
      ;;
    *)
      echo "run_experiments: unknown argument $1 (see --help)" >&2
      exit 2
      ;;
  esac
  shift
done
if [ -z "$data" ]; then
  echo "run_experiments: no data folder: give --data DIR or set ALEGO_DATA (the folder with" \
    "kitti_odometry/ and clustering_bench/)" >&2
  exit 2
fi
for needed in kitti_odometry/poses kitti_odometry/times kitti_odometry/seq07_frames0-4 \
  kitti_odometry/first10 clustering_bench/points_noground clustering_bench/labels; do
  if [ ! -d "$data/$needed" ]; then
    echo "run_experiments: $data/$needed: missing (expected the KITTI poses, times and scans and" \
      "the clustering benchmark; see docs/RESULTS.md)" >&2
    exit 1
  fi
done
data="$(cd "$data" && pwd)"

set --  # setup.sh hands its arguments to catkin_make
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
work="$ALEGO_ROOT/results/experiments${quick:+_quick}${foliage:+_foliage${foliage[1]}}"
mkdir -p "$work"
/usr/bin/python3 "$ALEGO_ROOT/scripts/experiments/suite.py" --bin "$ALEGO_BIN" \
  --root "$ALEGO_ROOT" --data "$data" --work "$work" --jobs "$jobs" "${quick[@]}" \
  "${foliage[@]}"
/usr/bin/python3 "$ALEGO_ROOT/scripts/experiments/report.py" --work "$work" --data "$data" \
  --root "$ALEGO_ROOT"
echo "run_experiments: docs/RESULTS.md and docs/images/results_*.png written (raw runs in $work)"
