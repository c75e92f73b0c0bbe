// The rotation spline passes through its rotations with a continuous angular velocity, turns at
// a constant rate through rotations that do, and its angular acceleration is that velocity's
// derivative.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/sim/rotation_spline.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

RotationSpline through(const std::function<Eigen::Matrix3d(double)>& rotation, int count,
                       double step) {
  std::vector<double> times;
  std::vector<Eigen::Matrix3d> rotations;
  for (int i = 0; i < count; ++i) {
    times.push_back(step * i);
    rotations.push_back(rotation(step * i));
  }
  return RotationSpline(times, rotations);
}

Eigen::Matrix3d wobbling(double t) {
  return (Eigen::AngleAxisd(0.8 * t + 0.3 * std::sin(2.0 * t), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(0.2 * std::sin(1.3 * t), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(0.1 * std::cos(0.9 * t), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

TEST(RotationSpline, PassesThroughItsRotationsWithContinuousAngularVelocity) {
  const RotationSpline spline = through(wobbling, 30, 0.1);
  for (int i = 0; i < 30; ++i)
    EXPECT_EQ(spline.at(0.1 * i).rotation, wobbling(0.1 * i)) << i;
  for (int i = 1; i < 29; ++i) {
    const double knot = 0.1 * i;
    const Eigen::Vector3d before = spline.at(knot - 1e-9).angular_velocity;
    const Eigen::Vector3d after = spline.at(knot + 1e-9).angular_velocity;
    EXPECT_LT((after - before).norm(), 1e-6) << i;
  }
}

TEST(RotationSpline, TurnsAtAConstantRateThroughRotationsThatDo) {
  const Eigen::Vector3d rate(0.3, -0.2, 0.9);  // rad/s, body frame
  const RotationSpline spline = through([&](double t) { return rotation_exp(rate * t); }, 20, 0.1);
  for (double t = 0.0; t < 1.9; t += 0.0137) {
    const RotationSpline::State state = spline.at(t);
    EXPECT_TRUE(state.angular_velocity.isApprox(rate, 1e-9)) << t;
    EXPECT_LT(state.angular_acceleration.norm(), 1e-6) << t;
    EXPECT_TRUE(state.rotation.isApprox(rotation_exp(rate * t), 1e-9)) << t;
  }
}

TEST(RotationSpline, AngularVelocityAndAccelerationAreTheRotationsDerivatives) {
  const RotationSpline spline = through(wobbling, 30, 0.1);
  constexpr double h = 1e-5;
  for (double t = 0.213; t < 2.8; t += 0.1) {  // inside intervals
    const RotationSpline::State state = spline.at(t);
    const Eigen::Vector3d rate =
        rotation_log(spline.at(t - h).rotation.transpose() * spline.at(t + h).rotation) / (2.0 * h);
    EXPECT_LT((state.angular_velocity - rate).norm(), 1e-6) << t;
    const Eigen::Vector3d acceleration =
        (spline.at(t + h).angular_velocity - spline.at(t - h).angular_velocity) / (2.0 * h);
    EXPECT_LT((state.angular_acceleration - acceleration).norm(), 1e-4) << t;
    // And the spline follows the rotations it was given between them.
    EXPECT_LT(rotation_log(state.rotation.transpose() * wobbling(t)).norm(), 2e-3) << t;
  }
}
