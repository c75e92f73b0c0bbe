#!/usr/bin/env bash
# Plays a KITTI-style sequence folder (KITTI's own, or lidar_sim's with --sensor hdl64e) through the
# ROS graph with rviz and saves a screenshot of rviz three quarters of the way through the drive.
#   scripts/rviz_screenshot.sh SEQUENCE_DIR OUT.png [RATE]
# Without a display rviz runs in a virtual one (Xvfb). Needs the workspace scripts/setup.sh built.
set -euo pipefail

if (($# < 2)); then
  echo "usage: scripts/rviz_screenshot.sh SEQUENCE_DIR OUT.png [RATE]" >&2
  exit 2
fi
sequence=$1
screenshot=$(realpath -m "$2")
rate=${3:-0.5}
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="${ALEGO_WS:-$ROOT/.ws}"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
if [ ! -f "$WS/devel/setup.bash" ]; then
  echo "rviz_screenshot: no workspace at $WS: run scripts/setup.sh first" >&2
  exit 1
fi
set +u
source "$WS/devel/setup.bash"
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

bag="$work/sequence.bag"
# Seconds of playback to the screenshot: three quarters of the sequence's times.txt.
until_screenshot=$(awk -v rate="$rate" 'NR == 1 {first = $1} {last = $1}
  END {printf "%.1f", 0.75 * (last - first) / rate}' "$sequence/times.txt")
"$WS/devel/lib/adaptive_lego_loam/kitti_to_bag" --input "$sequence" --output "$bag" >/dev/null

# Inside the X display: the graph, rviz and the bag on a master of their own, and a screenshot of
# the rviz window once the player has played the bag that long.
cat >"$work/inside_display.sh" <<EOF
#!/usr/bin/env bash
export ROS_MASTER_URI=http://localhost:\$(( 20000 + RANDOM % 20000 ))
roslaunch adaptive_lego_loam kitti_bag.launch bag:="$bag" rate:=$rate >"$work/launch.log" 2>&1 &
launch=\$!
for second in \$(seq 1 120); do
  sleep 1
  rosnode list 2>/dev/null | grep -q '^/player$' && break
done
sleep \$(awk 'BEGIN {print 1 + $until_screenshot}')
# rviz's first start on a machine can take longer than that (its window missing, or not drawn
# yet: a black image): a few more tries, until the picture is not one flat colour.
status=1
for attempt in \$(seq 1 15); do
  window=\$(xwininfo -root -tree | awk '/RViz/ {print \$1; exit}')
  if [ -n "\$window" ] && import -window "\$window" "$screenshot" &&
      [ "\$(convert "$screenshot" -format '%[fx:standard_deviation > 0.01]' info:)" = 1 ]; then
    status=0
    break
  fi
  rm -f "$screenshot"
  sleep 2
done
kill -INT \$launch
wait \$launch 2>/dev/null
exit \$status
EOF
chmod +x "$work/inside_display.sh"
rm -f "$screenshot"
if [ -n "${DISPLAY:-}" ]; then
  "$work/inside_display.sh" || true
else
  xvfb-run -a -s "-screen 0 1600x1050x24" "$work/inside_display.sh" || true
fi
if [ ! -s "$screenshot" ]; then
  echo "rviz_screenshot: no screenshot taken: the rviz window did not appear or stayed blank" >&2
  tail -n 20 "$work/launch.log" >&2 || true
  exit 1
fi
echo "rviz_screenshot: $screenshot"
