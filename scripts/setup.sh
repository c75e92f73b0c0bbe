#!/usr/bin/env bash
# Installs the Debian packages the project needs (only those missing, quietly), then builds the
# package (Release) in a catkin workspace at .ws/ inside the checkout (git-ignored).
# Sourced by demo.sh and test.sh; can be run alone. Extra arguments go to catkin_make.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="${ALEGO_WS:-$ROOT/.ws}"
# Debian's python3 must win over any pyenv/conda python3 on PATH: ROS's Python lives there.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"

PACKAGES=(
  build-essential cmake catkin ros-base-dev ros-message-generation ros-message-runtime
  libroscpp-dev libroslib-dev libstd-msgs-dev libsensor-msgs-dev libgeometry-msgs-dev
  libnav-msgs-dev libvisualization-msgs-dev libros-rosgraph-msgs-dev
  libtf2-ros-dev libtf2-eigen-dev libtf2-geometry-msgs-dev librosbag-dev python3-rosbag
  python3-rostest librostest-dev python3-roslaunch python3-catkin-pkg libnodelet-dev
  pluginlib-dev libdiagnostic-updater-dev libdiagnostic-msgs-dev python3-diagnostic-msgs
  libpcl-dev libpcl-conversions-dev libpcl-ros-dev libeigen3-dev libceres-dev libyaml-cpp-dev
  libcli11-dev nlohmann-json3-dev libembree-dev libgtest-dev googletest libbenchmark-dev
  python3-numpy python3-matplotlib python3-scipy
  rviz xvfb xauth x11-utils imagemagick
  python3-std-msgs python3-geometry-msgs python3-sensor-msgs python3-nav-msgs python3-tf2-msgs
  python3-visualization-msgs python3-rosgraph-msgs
)

missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

mkdir -p "$WS/src"
ln -sfn "$ROOT" "$WS/src/adaptive_lego_loam"
echo "setup: building in $WS (a few minutes the first time; log: $WS/build.log)"
if ! catkin_make -C "$WS" -DCMAKE_BUILD_TYPE=Release \
    -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
    -j2 "$@" >"$WS/build.log" 2>&1; then
  tail -n 60 "$WS/build.log"
  echo "setup: build failed (full log: $WS/build.log)" >&2
  exit 1
fi
export ALEGO_WS="$WS" ALEGO_ROOT="$ROOT"
export ALEGO_BIN="$WS/devel/lib/adaptive_lego_loam"
