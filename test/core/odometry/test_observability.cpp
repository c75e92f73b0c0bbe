#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/core/odometry/residuals.h"

using namespace adaptive_lego_loam;

TEST(Observability, SigmasAlongThePrincipalDirections) {
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  information.diagonal() << 1e4, 1e4, 1e4, 100.0, 1e4, 1e6;  // x known to 10 cm, y 1 cm, z 1 mm
  const Observability seen = observability(information);
  EXPECT_NEAR(seen.weakest_sigma(), 0.1, 1e-9);
  EXPECT_NEAR(std::fabs(seen.weakest_direction().x()), 1.0, 1e-9);
  EXPECT_NEAR(seen.translation_sigma(2), 0.001, 1e-9);
  EXPECT_NEAR(seen.rotation_sigma(0), 0.01, 1e-9);
}

TEST(Observability, AFreeDirectionIsInfiniteAndSoIsWhatHangsOnIt) {
  // Planes facing y and z only: nothing along x.
  Correspondences matches;
  for (int i = 0; i < 50; ++i) {
    const double s = i * 0.2;
    matches.planes.push_back({Eigen::Vector3d(s, 2.0, 0.1 * i), Eigen::Vector3d::UnitY(), -2.0});
    matches.planes.push_back({Eigen::Vector3d(s, -0.1 * i, -1.5), Eigen::Vector3d::UnitZ(), 1.5});
  }
  const Observability seen =
      observability(correspondence_information(matches, Eigen::Isometry3d::Identity(), 1.0, 0.02));
  EXPECT_TRUE(std::isinf(seen.weakest_sigma()));
  EXPECT_NEAR(std::fabs(seen.weakest_direction().x()), 1.0, 1e-6);
  EXPECT_LT(seen.translation_sigma(1), 0.01);
}

TEST(Observability, CorrespondenceInformationIsTheJacobiansOverTheNoise) {
  // One plane facing x at the origin: a translation along x moves its residual one for one.
  Correspondences matches;
  matches.planes.push_back({Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d::UnitX(), -2.0});
  const Eigen::Matrix<double, 6, 6> information =
      correspondence_information(matches, Eigen::Isometry3d::Identity(), 1.0, 0.1);
  EXPECT_NEAR(information(3, 3), 100.0, 1e-9);
  EXPECT_NEAR(information(4, 4), 0.0, 1e-12);
  // A turn about z moves the point (2, 0, 0) along y: no residual for a plane facing x.
  EXPECT_NEAR(information(2, 2), 0.0, 1e-12);
}

TEST(Observability, CovarianceInvertsTheInformationAndCapsWhatItLeavesOpen) {
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  information.diagonal() << 1e6, 1e6, 1e6, 0.0, 1e4, 1e-6;  // x open, z nearly
  const Eigen::Matrix<double, 6, 6> covariance = covariance_from_information(information, 100.0);
  EXPECT_NEAR(covariance(0, 0), 1e-6, 1e-12);
  EXPECT_NEAR(covariance(4, 4), 1e-4, 1e-10);
  EXPECT_DOUBLE_EQ(covariance(3, 3), 100.0);
  EXPECT_DOUBLE_EQ(covariance(5, 5), 100.0);
  EXPECT_TRUE(covariance.allFinite());
  // A direction off the axes: its variance along it, none across.
  const Eigen::Vector3d along = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  Eigen::Matrix<double, 6, 6> diagonal_road = Eigen::Matrix<double, 6, 6>::Identity() * 1e4;
  diagonal_road.bottomRightCorner<3, 3>() -= 1e4 * along * along.transpose();
  const Eigen::Matrix<double, 6, 6> open = covariance_from_information(diagonal_road, 100.0);
  EXPECT_NEAR(along.dot(open.bottomRightCorner<3, 3>() * along), 100.0, 1e-6);
  const Eigen::Vector3d across(-along.y(), along.x(), 0.0);
  EXPECT_NEAR(across.dot(open.bottomRightCorner<3, 3>() * across), 1e-4, 1e-9);
}

TEST(Observability, HeldAlongTakesTheHeldComponentAndKeepsTheRest) {
  const Eigen::Vector3d direction = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const Eigen::Vector3d registered(0.2, 0.1, 0.05);  // fell back toward standing still
  const Eigen::Vector3d guess(1.0, 1.0, 0.0);
  const Eigen::Vector3d held = held_along(registered, guess, direction);
  EXPECT_NEAR(direction.dot(held), direction.dot(guess), 1e-12);
  const Eigen::Vector3d across = Eigen::Vector3d(1.0, -1.0, 0.0).normalized();
  EXPECT_NEAR(across.dot(held), across.dot(registered), 1e-12);
  EXPECT_NEAR(held.z(), registered.z(), 1e-12);
}
