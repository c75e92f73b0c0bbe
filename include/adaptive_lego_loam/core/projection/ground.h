#pragma once
// docs/METHOD.md, step 2: LeGO-LOAM's ground test on the lower rows of the range image.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

// Marks cell pairs (row, upper row) in the lowest `ground_rows` rows as ground where the slope
// between the two points is within `slope_tolerance_deg` of the sensor's mount angle. The upper
// row is the first at least `row_gap_deg` above (0: the next row, LeGO-LOAM's): beams a fraction
// of a degree apart see a wall's points a few millimetres above each other, which range noise
// tilts to any slope. `ground` gets one flag per cell (1 = ground). Returns the number of ground
// cells.
int mark_ground(const RangeImage& image, int ground_rows, double mount_angle_deg,
                double slope_tolerance_deg, std::vector<uint8_t>& ground, double row_gap_deg = 0.0);

}  // namespace adaptive_lego_loam
