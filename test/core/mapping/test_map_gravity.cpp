#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/mapping/map_gravity.h"

using namespace adaptive_lego_loam;

TEST(MapGravity, LearnsTheMapsUpFromTheFirstScansThenHoldsIt) {
  // The map's first scan was pitched 3 deg: in the map frame, up leans back.
  const Eigen::Matrix3d pitched =
      Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  MapGravity gravity(10);
  GravityPrior level;
  level.up = Eigen::Vector3d::UnitZ();
  level.covariance = Eigen::Matrix3d::Identity() * 1e-6;
  for (int scan = 0; scan < 9; ++scan) {
    gravity.add(pitched.transpose(), level);
    EXPECT_FALSE(gravity.up());
  }
  gravity.add(pitched.transpose(), level);
  ASSERT_TRUE(gravity.up());
  EXPECT_LT((*gravity.up() - pitched.transpose() * Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // Held: later scans do not move it.
  gravity.add(Eigen::Matrix3d::Identity(), level);
  EXPECT_LT((*gravity.up() - pitched.transpose() * Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}
