#include "adaptive_lego_loam/sim/lidar_model.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam::sim {
namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw ConfigError("simulator: " + what);
}

}  // namespace

LidarModel::LidarModel(const SensorParams& sensor, const SimSensorOptions& options)
    : sensor_(sensor), options_(options) {
  validate(sensor_, sensor_.name);
  check(options.columns >= 16 && options.columns <= 20000,
        "columns = " + std::to_string(options.columns) + ": expected an integer in [16, 20000]");
  check(options.range_noise_m >= 0.0 && options.range_noise_m <= 1.0,
        "range noise = " + std::to_string(options.range_noise_m) + ": expected metres in [0, 1]");
  check(options.beam_divergence_mrad >= 0.0 && options.beam_divergence_mrad <= 50.0,
        "beam divergence = " + std::to_string(options.beam_divergence_mrad) +
            ": expected mrad in [0, 50]");
  check(options.echo_merge_distance_m >= 0.0 && options.echo_merge_distance_m <= 10.0,
        "echo merge distance = " + std::to_string(options.echo_merge_distance_m) +
            ": expected metres in [0, 10]");
  check(options.full_return_incidence_deg > 0.0 &&
            options.full_return_incidence_deg < options.no_return_incidence_deg &&
            options.no_return_incidence_deg <= 90.0,
        "incidence limits: expected 0 < full-return angle < no-return angle <= 90 deg");
  for (int beam = 0; beam < sensor_.rows; ++beam) {
    const double elevation = sensor_.beam_angles_deg[beam] * M_PI / 180.0;
    cos_elevation_.push_back(std::cos(elevation));
    sin_elevation_.push_back(std::sin(elevation));
    const double offset = sensor_.beam_offsets_m.empty() ? 0.0 : sensor_.beam_offsets_m[beam];
    beam_origins_.emplace_back(0.0, 0.0, offset);
  }
  rings_.assign(sensor_.rows, -1);
  for (int ring = 0; ring < static_cast<int>(sensor_.ring_to_row.size()); ++ring) {
    const int row = sensor_.ring_to_row[ring];
    if (row >= 0 && rings_[row] < 0) rings_[row] = ring;
  }
  for (int beam = 0; beam < sensor_.rows; ++beam) {
    if (sensor_.ring_to_row.empty()) rings_[beam] = beam;
    check(rings_[beam] >= 0, "sensor.ring_to_row maps no ring to row " + std::to_string(beam));
  }
  for (int column = 0; column < options_.columns; ++column) {
    cos_azimuth_.push_back(std::cos(azimuth(column)));
    sin_azimuth_.push_back(std::sin(azimuth(column)));
  }
  cos_full_return_ = std::cos(options.full_return_incidence_deg * M_PI / 180.0);
  cos_no_return_ = std::cos(options.no_return_incidence_deg * M_PI / 180.0);
}

double LidarModel::azimuth(int column) const {
  return M_PI - 2.0 * M_PI * column / options_.columns;
}

double LidarModel::column_time(int column) const {
  return sensor_.scan_period * column / options_.columns;
}

}  // namespace adaptive_lego_loam::sim
