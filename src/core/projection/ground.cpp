#include "adaptive_lego_loam/core/projection/ground.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {

int mark_ground(const RangeImage& image, int ground_rows, double mount_angle_deg,
                double slope_tolerance_deg, std::vector<uint8_t>& ground, double row_gap_deg) {
  ground.assign(image.size(), 0);
  const int last_lower_row = std::min(ground_rows, image.rows() - 1);
  // The slope atan2(dz, dxy) lies in [mount - tolerance, mount + tolerance] exactly when dz lies
  // between tan() of the two bounds times dxy (dxy >= 0 and both bounds within +-90 deg).
  const double lowest_deg = std::max(mount_angle_deg - slope_tolerance_deg, -89.9);
  const double highest_deg = std::min(mount_angle_deg + slope_tolerance_deg, 89.9);
  const float tan_lowest = static_cast<float>(std::tan(lowest_deg * M_PI / 180.0));
  const float tan_highest = static_cast<float>(std::tan(highest_deg * M_PI / 180.0));
  const std::vector<double>& elevation = image.geometry().row_elevation_rad;
  const double row_gap_rad = row_gap_deg * M_PI / 180.0;
  for (int row = 0; row < last_lower_row; ++row) {
    int upper_row = row + 1;
    while (upper_row < last_lower_row && elevation[upper_row] - elevation[row] < row_gap_rad)
      ++upper_row;
    if (elevation[upper_row] - elevation[row] < row_gap_rad) break;  // none far enough above
    for (int col = 0; col < image.cols(); ++col) {
      const int lower = image.cell(row, col);
      const int upper = image.cell(upper_row, col);
      if (!image.occupied(lower) || !image.occupied(upper)) continue;
      const ScanPoint& a = image.point(lower);
      const ScanPoint& b = image.point(upper);
      const float dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
      const float horizontal = std::sqrt(dx * dx + dy * dy);
      if (dz >= tan_lowest * horizontal && dz <= tan_highest * horizontal) {
        ground[lower] = 1;
        ground[upper] = 1;
      }
    }
  }
  int count = 0;
  for (uint8_t flag : ground)
    count += flag;
  return count;
}

}  // namespace adaptive_lego_loam
