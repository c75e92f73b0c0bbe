#pragma once
// The simulated sensor: beam elevations and origins from the project's sensor config, columns
// (firings per turn), range noise, dropouts at grazing incidence, intensity.

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"

namespace adaptive_lego_loam::sim {

struct SimSensorOptions {
  int columns = 1800;           // firings per turn; each fires every beam once
  double range_noise_m = 0.02;  // standard deviation of the Gaussian range error
  // Dropouts at grazing incidence: every return comes back up to `full_return_incidence_deg`,
  // none past `no_return_incidence_deg`, and the chance falls linearly in between.
  double full_return_incidence_deg = 70.0;
  double no_return_incidence_deg = 86.0;
  // The sensor moves during the sweep and each column is reported in the sensor's frame at its
  // own firing time (a raw, skewed scan); the sweep ends at the frame's time and pose, as a
  // Velodyne driver stamps a scan with its last packet. Off: every ray leaves from the frame's
  // pose (a perfectly de-skewed scan, as KITTI ships).
  bool motion_distortion = true;
  // Beam divergence: the pulse's footprint grows with range (3 mrad: 3 cm at 10 m), and where it
  // falls on surfaces at different ranges (an edge, foliage) their echoes closer than
  // echo_merge_distance merge into one at their energy-weighted range (a mixed pixel); the
  // strongest echo is reported. Each beam casts its centre ray and four at the footprint's rim.
  // 0: thin beams, one ray each.
  double beam_divergence_mrad = 0.0;
  double echo_merge_distance_m = 0.5;
};

class LidarModel {
 public:
  // Throws ConfigError naming the bad option.
  LidarModel(const SensorParams& sensor, const SimSensorOptions& options);

  const SensorParams& sensor() const { return sensor_; }
  const SimSensorOptions& options() const { return options_; }
  int beams() const { return static_cast<int>(beam_origins_.size()); }
  int columns() const { return options_.columns; }

  // The ring the driver reports beam `beam` (0 = lowest) with: the config's ring_to_row read
  // backwards (Ouster's drivers number rings from the top beam), else the beam.
  int ring(int beam) const { return rings_[beam]; }
  // Beam `beam` leaves from here, in the sensor frame.
  const Eigen::Vector3d& beam_origin(int beam) const { return beam_origins_[beam]; }
  // Unit direction of beam `beam` at column `column`, sensor frame.
  Eigen::Vector3d direction(int beam, int column) const {
    return {cos_elevation_[beam] * cos_azimuth_[column],
            cos_elevation_[beam] * sin_azimuth_[column], sin_elevation_[beam]};
  }
  // Column 0 looks backwards (azimuth pi) and the head turns clockwise seen from above, as a
  // Velodyne's does.
  double azimuth(int column) const;
  // Firing time of the column, seconds after the sweep starts.
  double column_time(int column) const;

  // Chance that a return at this cosine of incidence comes back.
  double return_probability(double cos_incidence) const {
    return std::clamp((cos_incidence - cos_no_return_) / (cos_full_return_ - cos_no_return_), 0.0,
                      1.0);
  }

 private:
  SensorParams sensor_;
  SimSensorOptions options_;
  std::vector<Eigen::Vector3d> beam_origins_;
  std::vector<int> rings_;
  std::vector<double> cos_elevation_, sin_elevation_;
  std::vector<double> cos_azimuth_, sin_azimuth_;
  double cos_full_return_ = 0.0, cos_no_return_ = 0.0;
};

}  // namespace adaptive_lego_loam::sim
