#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "adaptive_lego_loam/core/common/fast_atan2.h"

using namespace adaptive_lego_loam;

TEST(FastAtan2, MatchesStdAtan2) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-50.f, 50.f);
  float worst = 0.f;
  for (int i = 0; i < 100000; ++i) {
    const float y = coordinate(rng), x = coordinate(rng);
    worst = std::max(worst, std::fabs(fast_atan2(y, x) - std::atan2(y, x)));
  }
  EXPECT_LT(worst, 2e-5f);
  EXPECT_NEAR(fast_atan2(0.f, -1.f), float(M_PI), 1e-5f);
  EXPECT_NEAR(fast_atan2(-1.f, 0.f), -float(M_PI) / 2, 1e-5f);
}
