#pragma once
// Real KITTI scans through the ambient filter, and message headers, for the conversion tests.

#include <gtest/gtest.h>
#include <std_msgs/Header.h>

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/io/scan_files.h"

namespace adaptive_lego_loam::test {

inline const std::string kScans = std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/";

inline Config kitti_config() {
  return load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
}

// The ambient filter's result on KITTI 07 frame `index`.
inline AmbientFilterResult filter_frame(AmbientFilter& filter, int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%010d.bin", index);
  AmbientFilterResult result;
  filter.process(read_kitti_bin(kScans + name), result);
  return result;
}

inline std_msgs::Header header_at(double seconds, const std::string& frame = "velodyne") {
  std_msgs::Header header;
  header.stamp.fromSec(seconds);
  header.frame_id = frame;
  return header;
}

inline void expect_same_points(const std::vector<ScanPoint>& a, const std::vector<ScanPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].z, b[i].z) << i;
    ASSERT_EQ(a[i].intensity, b[i].intensity) << i;
  }
}

inline void expect_same_cloud(const Cloud& a, const Cloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].z, b[i].z) << i;
    ASSERT_EQ(a[i].intensity, b[i].intensity) << i;
  }
}

}  // namespace adaptive_lego_loam::test
