// The building blocks of odometry and mapping: the KD-tree and the voxel map against a brute-force
// search, and the registration cost functions' analytic Jacobians against finite differences.

#include <gtest/gtest.h>
#include <pcl/filters/voxel_grid.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/mapping/local_map.h"
#include "adaptive_lego_loam/core/odometry/residuals.h"
#include "adaptive_lego_loam/core/spatial/kdtree.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"
#include "adaptive_lego_loam/core/spatial/voxel_map.h"

using namespace adaptive_lego_loam;

namespace {

Correspondences some_matches() {
  Correspondences matches;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  auto vector = [&] {
    return Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  };
  for (int i = 0; i < 6; ++i) {
    // Near and far from the line or plane: inside and beyond the Huber threshold.
    matches.lines.push_back({vector(), vector(), vector().normalized()});
    const Eigen::Vector3d normal = vector().normalized();
    matches.planes.push_back({vector(), normal, 0.1 * coordinate(random)});
  }
  return matches;
}

// Central differences of `cost` in each entry of each parameter block.
void expect_jacobians_match(const ceres::CostFunction& cost, std::vector<double*> blocks) {
  const int residuals = cost.num_residuals();
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  std::vector<std::vector<double>> jacobians(blocks.size());
  std::vector<double*> jacobian_pointers;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    jacobians[b].resize(residuals * sizes[b]);
    jacobian_pointers.push_back(jacobians[b].data());
  }
  std::vector<double> r(residuals), plus(residuals), minus(residuals);
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r.data(), jacobian_pointers.data()));
  const double step = 1e-6;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    for (int entry = 0; entry < sizes[b]; ++entry) {
      const double saved = blocks[b][entry];
      blocks[b][entry] = saved + step;
      cost.Evaluate(blocks.data(), plus.data(), nullptr);
      blocks[b][entry] = saved - step;
      cost.Evaluate(blocks.data(), minus.data(), nullptr);
      blocks[b][entry] = saved;
      for (int row = 0; row < residuals; ++row) {
        EXPECT_NEAR(jacobians[b][row * sizes[b] + entry], (plus[row] - minus[row]) / (2 * step),
                    1e-5)
            << "block " << b << " entry " << entry << " row " << row;
      }
    }
  }
}

}  // namespace

TEST(RegistrationCost, EulerJacobianMatchesFiniteDifferences) {
  const Correspondences matches = some_matches();
  double pose[6] = {0.1, -0.2, 0.3, 0.5, -0.4, 0.2};
  for (MatchKinds kinds : {MatchKinds::kBoth, MatchKinds::kLines, MatchKinds::kPlanes}) {
    const EulerRegistrationCost cost(matches, kinds, 0.5);
    expect_jacobians_match(cost, {pose});
  }
  EXPECT_EQ(EulerRegistrationCost(matches, MatchKinds::kBoth, 0.5).num_residuals(), 6 * 3 + 6);
}

TEST(RegistrationCost, QuaternionJacobianMatchesFiniteDifferences) {
  const Correspondences matches = some_matches();
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  double rotation[4] = {q.x(), q.y(), q.z(), q.w()};
  double translation[3] = {0.3, -0.1, 0.2};
  const QuaternionRegistrationCost cost(matches, 0.5);
  expect_jacobians_match(cost, {rotation, translation});
}

// The cost equals the sum of per-correspondence Huber losses of the point-to-line and
// point-to-plane distances.
TEST(RegistrationCost, CostIsHuberOfDistances) {
  const Correspondences matches = some_matches();
  const double delta = 0.5;
  double pose[6] = {0.1, -0.2, 0.3, 0.5, -0.4, 0.2};
  const EulerRegistrationCost cost(matches, MatchKinds::kBoth, delta);
  std::vector<double> r(cost.num_residuals());
  const double* blocks[] = {pose};
  ASSERT_TRUE(cost.Evaluate(blocks, r.data(), nullptr));
  const Eigen::Isometry3d transform = euler_vector_to_pose(pose);
  auto huber = [delta](double s) {
    return s <= delta * delta ? s : 2 * delta * std::sqrt(s) - delta * delta;
  };
  double expected = 0.0;
  for (const LineMatch& line : matches.lines) {
    const Eigen::Vector3d moved = transform * line.point;
    expected += huber((moved - line.through).cross(line.direction).squaredNorm());
  }
  for (const PlaneMatch& plane : matches.planes) {
    const double distance = plane.normal.dot(transform * plane.point) + plane.offset;
    expected += huber(distance * distance);
  }
  double actual = 0.0;
  for (double value : r)
    actual += value * value;
  EXPECT_NEAR(actual, expected, 1e-9 * expected);
}
