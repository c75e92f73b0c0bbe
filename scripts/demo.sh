#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the embedded default data: the real
# KITTI sequence 07 frames in test/data, segmented with the KITTI config.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

"$ALEGO_BIN/segment_scans" --config "$ALEGO_ROOT/config/kitti.yaml" \
  "$ALEGO_ROOT/test/data/kitti_seq07/velodyne"
