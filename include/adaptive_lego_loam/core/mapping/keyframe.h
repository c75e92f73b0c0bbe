#pragma once
// Keyframes: the scans the map is built from, with their features in the sensor frame, packed
// (a long run keeps thousands of them).

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/common/packed_cloud.h"

namespace adaptive_lego_loam {

struct Keyframe {
  int index = 0;                                           // position in the keyframe list
  int frame = 0;                                           // input frame it was taken at
  double stamp = 0.0;                                      // s
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // sensor pose in the map frame
  // Voxel-filtered, sensor frame: the sharp and less sharp edges; the flat and less flat surfaces
  // with LeGO-LOAM's outlier cloud (used as surfaces).
  PackedCloudPtr corners, surfaces;
  // Scan-to-map found directions its scan does not constrain (a tunnel, a bare wall): ICP cannot
  // tell where such a keyframe is along them, so it takes no part in loop closure.
  bool degenerate = false;

  bool has_clouds() const { return corners && surfaces; }
};

}  // namespace adaptive_lego_loam
