#!/usr/bin/env bash
# The main job on the embedded default data, showing what the adaptive filter does:
#   1. the real KITTI sequence 07 scans in test/data, against KITTI's ground truth;
#   2. three short simulated HDL-64E drives, generated here by lidar_sim: a highway along KITTI 01's
#      real trajectory (open, weakly constrained along the road), an urban street and a narrow
#      road through vegetation (cluttered),
# each run with the adaptive beta0 and, for contrast, LeGO-LOAM's fixed 60 deg. Prints t_err, the
# per-scan error, mean mu and frames per second, and writes plots (scripts/plot_run.py).
#   scripts/demo.sh [--rviz]   --rviz: also plays the highway drive through the ROS graph with
#                              rviz (under Xvfb when there is no display) and saves a screenshot.
set -euo pipefail

with_rviz=0
for argument in "$@"; do
  case "$argument" in
    --rviz) with_rviz=1 ;;
    -h | --help)
      sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"
      exit 0
      ;;
    *)
      echo "demo: unknown argument $argument (see scripts/demo.sh --help)" >&2
      exit 2
      ;;
  esac
done

set --  # setup.sh hands its arguments to catkin_make
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
BIN="$ALEGO_BIN"
DATA="$ALEGO_ROOT/test/data"
OUT="${ALEGO_DEMO:-$ALEGO_WS/demo}"
FRAMES=200
SEED=1
rm -rf "$OUT"
mkdir -p "$OUT"
started=$(date +%s)

# run_sequence on SEQUENCE with CONFIG into OUT/NAME (extra arguments after NAME), then its
# evaluation against the sequence's ground truth into OUT/NAME/metrics.json.
run() {
  local sequence=$1 config=$2 name=$3
  shift 3
  mkdir -p "$(dirname "$OUT/$name")"
  "$BIN/run_sequence" --config "$config" --input "$sequence" --output "$OUT/$name" "$@" \
    >"$OUT/$name.log" 2>&1 || { tail -n 3 "$OUT/$name.log" >&2; return 1; }
  "$BIN/evaluate_odometry" --gt "$sequence/poses.txt" --est "$OUT/$name/poses_kitti.txt" \
    --calib "$sequence/calib.txt" --json "$OUT/$name/metrics.json" >>"$OUT/$name.log" 2>&1
}

# Both thresholds on one sequence, side by side on the two cores.
run_both() {
  local sequence=$1 config=$2 name=$3
  run "$sequence" "$config" "$name/adaptive" --adaptive &
  local adaptive=$!
  run "$sequence" "$config" "$name/fixed60" --beta0 60
  wait "$adaptive"
  mkdir -p "$OUT/$name/plots"
  /usr/bin/python3 "$ALEGO_ROOT/scripts/plot_run.py" "$OUT/$name/adaptive" "$OUT/$name/fixed60" \
    --label adaptive --label "fixed 60 deg" --gt "$sequence/poses.txt" \
    --calib "$sequence/calib.txt" --title "$name" --output "$OUT/$name/plots" >/dev/null
}

echo "demo: real KITTI 07, frames 0-4 (test/data)"
run_both "$DATA/kitti_seq07" "$ALEGO_ROOT/config/kitti.yaml" kitti07

simulate() {
  local scenario=$1
  shift
  "$BIN/lidar_sim" --scenario "$scenario" --sensor hdl64e --frames "$FRAMES" --seed "$SEED" \
    --output "$OUT/sequences/$scenario" "$@" >"$OUT/sequences/$scenario.log" 2>&1
}
mkdir -p "$OUT/sequences"
echo "demo: simulating $FRAMES HDL-64E scans each of highway (KITTI 01's trajectory), urban, vegetation"
simulate highway --trajectory "$DATA/kitti_poses/01_frames0-199.txt" \
  --trajectory-times "$DATA/kitti_poses/01_times0-199.txt" &
simulate urban
wait
simulate vegetation
for terrain in highway urban vegetation; do
  echo "demo: $terrain, adaptive and fixed 60 deg"
  run_both "$OUT/sequences/$terrain" "$ALEGO_ROOT/config/kitti.yaml" "$terrain"
done

echo
/usr/bin/python3 "$ALEGO_ROOT/scripts/demo_table.py" "$OUT" kitti07 highway urban vegetation

if ((with_rviz)); then
  echo
  "$ALEGO_ROOT/scripts/rviz_screenshot.sh" "$OUT/sequences/highway" "$OUT/rviz.png"
fi

echo
echo "demo: done in $(($(date +%s) - started)) s. Outputs in $OUT:"
echo "  <sequence>/{adaptive,fixed60}/  run_sequence outputs (poses, timing.csv, degeneration.csv)"
echo "  <sequence>/plots/               trajectory.png, mu_beta0.png, per_scan_error.png, timing.png"
echo "  sequences/                      the simulated drives (KITTI-style folders)"
if ((with_rviz)); then echo "  rviz.png                        rviz during the highway drive"; fi
