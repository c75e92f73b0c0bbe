#pragma once
// atan2 to about 1e-5 rad, several times faster than std::atan2: for where a column index or a
// sweep fraction is all that is needed. Inline: it is called once per point.

#include <cmath>

namespace adaptive_lego_loam {

inline float fast_atan2(float y, float x) {
  const float abs_y = std::fabs(y);
  const float abs_x = std::fabs(x);
  if (abs_x == 0.f && abs_y == 0.f) return 0.f;
  const bool steep = abs_y > abs_x;
  const float z = steep ? abs_x / abs_y : abs_y / abs_x;  // in [0, 1]
  const float z2 = z * z;
  // Minimax polynomial for atan on [0, 1] (max error about 1e-5 rad).
  float angle =
      z * (0.99997726f +
           z2 * (-0.33262347f +
                 z2 * (0.19354346f + z2 * (-0.11643287f + z2 * (0.05265332f - z2 * 0.01172120f)))));
  constexpr float kHalfPi = 1.57079632679f;
  constexpr float kPi = 3.14159265359f;
  if (steep) angle = kHalfPi - angle;
  if (x < 0.f) angle = kPi - angle;
  return y < 0.f ? -angle : angle;
}

}  // namespace adaptive_lego_loam
