#pragma once
// The scan as the core sees it: plain points with optional ring and time, no ROS, no PCL.

#include <cstdint>
#include <limits>
#include <vector>

namespace adaptive_lego_loam {

struct ScanPoint {
  float x = 0.f;
  float y = 0.f;
  float z = 0.f;
  float intensity = 0.f;
  float time = 0.f;   // seconds since the start of the sweep; valid when Scan::has_time
  int32_t ring = -1;  // laser index as the driver numbers it; valid when Scan::has_ring
};

struct Scan {
  std::vector<ScanPoint> points;
  double stamp = 0.0;  // seconds
  bool has_ring = false;
  bool has_time = false;
};

}  // namespace adaptive_lego_loam
