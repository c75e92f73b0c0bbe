#pragma once
// Gravity without an IMU: walls stand vertical. The normals of a scan's near-vertical planar
// patches, turned into the map frame, must be horizontal; scan-to-map adds that as a weak prior on
// roll and pitch. Without it a sparse sensor's map tilts slowly (the VLP-16's ground constrains
// roll and pitch only relative to a map built from its own past poses), and the tilt becomes
// metres of height error on a long drive. The map frame's z axis (the first scan's) is up.

#include <Eigen/Core>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"

namespace adaptive_lego_loam {

// The normals (sensor frame, unit) of the planar patches of `points` (sensor frame) that
// `rotation` (sensor to map) turns to within max_tilt_deg of vertical walls above the sensor: a
// patch is the points in a 1 m cube, flat and spread in two directions. None when fewer than 20
// such patches are found.
std::vector<Eigen::Vector3d> wall_normals(const Cloud& points, const Eigen::Matrix3d& rotation,
                                          double max_tilt_deg);

}  // namespace adaptive_lego_loam
