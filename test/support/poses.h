#pragma once
// Poses for tests: a planar pose from x, y and yaw.

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace adaptive_lego_loam::test {

using Poses = std::vector<Eigen::Isometry3d>;

constexpr double kDeg = M_PI / 180.0;

// At (x, y, 0), turned by yaw_deg about z.
inline Eigen::Isometry3d planar(double x, double y, double yaw_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() << x, y, 0.0;
  return pose;
}

}  // namespace adaptive_lego_loam::test
