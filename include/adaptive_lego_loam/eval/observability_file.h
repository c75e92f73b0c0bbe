#pragma once
// A simulated sequence's observability.csv (lidar_sim writes it, sim/observability.h): per scan,
// its index and the 36 entries, row by row, of the true 6 x 6 information of point-to-plane
// residuals of its returns ([rotation about x, y, z (rad), translation along x, y, z (m)], sensor
// frame at the scan's time, with the sensor's range noise as sigma). Comment lines first.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace adaptive_lego_loam {

struct TrueObservability {
  int frame = 0;
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
};

// Scans in increasing frame order. Throws IoError "<path>:<line>: <what was expected>" on a line
// that is not a non-negative integer index (above the previous one) and 36 finite numbers, and
// on a file without scans.
std::vector<TrueObservability> read_observability_csv(const std::string& path);
std::vector<TrueObservability> parse_observability_csv(const std::string& text,
                                                       const std::string& source);

}  // namespace adaptive_lego_loam
