#pragma once
// Where gravity's up points in the map frame, learned from the first scans an IMU levels: each
// scan's up (its attitude in the map times the IMU's up in the sensor frame), averaged by how well
// the IMU knows it, then held. From then on gravity keeps the map's attitude level (the
// motion sensors' gravity prior in scan-to-map), as the first scans saw it.

#include <Eigen/Geometry>
#include <optional>

#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"

namespace adaptive_lego_loam {

class MapGravity {
 public:
  // Held after this many scans.
  explicit MapGravity(int scans = 50) : scans_(scans) {}
  // A scan's attitude in the map and the IMU's up in its frame.
  void add(const Eigen::Matrix3d& map_from_sensor, const GravityPrior& gravity);
  // The map frame's up, once held.
  std::optional<Eigen::Vector3d> up() const;

 private:
  int scans_;
  int added_ = 0;
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
};

}  // namespace adaptive_lego_loam
