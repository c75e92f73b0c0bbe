#pragma once
// The real KITTI HDL-64E scan the benchmarks time (sequence 07 frame 0, in test/data).

#include <string>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/io/scan_files.h"

namespace adaptive_lego_loam::bench {

struct KittiFrame {
  Config config = load_config(std::string(PROJECT_SOURCE_DIR) + "/config/kitti.yaml");
  Scan scan = read_kitti_bin(std::string(PROJECT_SOURCE_DIR) +
                             "/test/data/kitti_seq07/velodyne/0000000000.bin");
};

inline const KittiFrame& kitti_frame() {
  static const KittiFrame frame;
  return frame;
}

}  // namespace adaptive_lego_loam::bench
