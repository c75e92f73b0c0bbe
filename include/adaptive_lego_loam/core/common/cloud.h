#pragma once
// The point cloud type of the odometry and mapping stages (PCL, for its KD-trees, voxel filters
// and ICP). Only headers of those stages include this.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

using CloudPoint = pcl::PointXYZI;
using Cloud = pcl::PointCloud<CloudPoint>;
using CloudPtr = Cloud::Ptr;
using CloudConstPtr = Cloud::ConstPtr;

// A scan point's position with `intensity` in the intensity field (the stages keep a row there).
CloudPoint to_cloud_point(const ScanPoint& p, float intensity);

// `pose` applied to every point of `in` (intensity kept).
CloudPtr transform_cloud(const Cloud& in, const Eigen::Isometry3d& pose);

}  // namespace adaptive_lego_loam
