#pragma once
// docs/METHOD.md, step 2: LeGO-LOAM's ground test on the lower rows of the range image.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

// Marks cell pairs (row, row + 1) in the lowest `ground_rows` rows as ground where the slope
// between the two points is within `slope_tolerance_deg` of the sensor's mount angle. `ground`
// gets one flag per cell (1 = ground). Returns the number of ground cells.
int mark_ground(const RangeImage& image, int ground_rows, double mount_angle_deg,
                double slope_tolerance_deg, std::vector<uint8_t>& ground);

}  // namespace adaptive_lego_loam
