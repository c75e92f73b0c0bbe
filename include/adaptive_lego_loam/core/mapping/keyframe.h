#pragma once
// Keyframes: the scans the map is built from, with their features in the sensor frame.

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"

namespace adaptive_lego_loam {

struct Keyframe {
  int index = 0;                                           // position in the keyframe list
  int frame = 0;                                           // input frame it was taken at
  double stamp = 0.0;                                      // s
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // sensor pose in the map frame
  CloudPtr corners;                                        // sharp + less sharp edges, sensor frame
  CloudPtr surfaces;  // flat + less flat surfaces (down-sampled), sensor frame
  CloudPtr outliers;  // LeGO-LOAM's outlier cloud, sensor frame (used as surfaces)
};

}  // namespace adaptive_lego_loam
