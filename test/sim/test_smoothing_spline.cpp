// The spline through samples is C2 and exact at its knots; the smoothing spline keeps slow
// motion and takes out fast noise, whose second derivative would be an acceleration.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/sim/smoothing_spline.h"

using adaptive_lego_loam::sim::SmoothingSpline;

namespace {

// Samples of f at 10 Hz over [0, seconds].
template <typename F>
SmoothingSpline sampled(F f, double seconds, double cutoff_hz) {
  std::vector<double> times;
  const int count = static_cast<int>(std::lround(seconds * 10.0)) + 1;
  Eigen::MatrixXd values(count, 1);
  for (int i = 0; i < count; ++i) {
    times.push_back(0.1 * i);
    values(i, 0) = f(0.1 * i);
  }
  return SmoothingSpline(times, values, cutoff_hz);
}

}  // namespace

TEST(SmoothingSpline, PassesThroughItsSamplesWithContinuousSecondDerivative) {
  const std::vector<double> times = {0.0, 0.1, 0.25, 0.3, 0.55, 0.6};
  Eigen::MatrixXd values(6, 2);
  values << 0.0, 1.0, 0.4, -1.0, 1.1, 2.0, 1.0, 0.5, 2.5, 0.0, 2.6, 3.0;
  const SmoothingSpline spline(times, values);
  for (std::size_t i = 0; i < times.size(); ++i)
    EXPECT_EQ(spline.at(times[i]), Eigen::VectorXd(values.row(i).transpose())) << i;
  for (std::size_t i = 1; i + 1 < times.size(); ++i) {
    for (int derivative = 0; derivative <= 2; ++derivative) {
      const Eigen::VectorXd before = spline.at(times[i] - 1e-9, derivative);
      const Eigen::VectorXd after = spline.at(times[i] + 1e-9, derivative);
      EXPECT_LT((after - before).norm(), 1e-4) << "knot " << i << " derivative " << derivative;
    }
  }
  // Natural: no second derivative at the ends, and linear beyond them.
  EXPECT_NEAR(spline.at(0.0, 2).norm(), 0.0, 1e-12);
  EXPECT_TRUE(spline.at(-0.5).isApprox(spline.at(0.0) - 0.5 * spline.at(0.0, 1), 1e-12));
  EXPECT_TRUE(spline.at(1.6).isApprox(spline.at(0.6) + 1.0 * spline.at(0.6, 1), 1e-12));
}

TEST(SmoothingSpline, FollowsASinusoidsAcceleration) {
  const double omega = 2.0 * M_PI * 0.5;
  const SmoothingSpline spline = sampled([&](double t) { return std::sin(omega * t); }, 10.0, 0.0);
  // Within 1 % of the amplitude: a cubic's error at 20 samples a period.
  for (double t = 2.0; t < 8.0; t += 0.037)
    EXPECT_NEAR(spline.at(t, 2)(0), -omega * omega * std::sin(omega * t), 0.01 * omega * omega)
        << t;
}

// 1 cm of 4 Hz noise on a slow motion is 6 m/s^2 of acceleration through the samples; a 1 Hz
// cutoff takes it out and leaves the slow motion's.
TEST(SmoothingSpline, SmoothingRemovesFastNoiseAndKeepsSlowMotion) {
  const double slow = 2.0 * M_PI * 0.2, fast = 2.0 * M_PI * 4.0;
  const auto f = [&](double t) { return std::sin(slow * t) + 0.01 * std::sin(fast * t); };
  const SmoothingSpline through = sampled(f, 30.0, 0.0);
  const SmoothingSpline smoothed = sampled(f, 30.0, 1.0);
  double worst_through = 0.0, worst_smoothed = 0.0;
  for (double t = 5.0; t < 25.0; t += 0.013) {
    const double truth = -slow * slow * std::sin(slow * t);
    worst_through = std::max(worst_through, std::abs(through.at(t, 2)(0) - truth));
    worst_smoothed = std::max(worst_smoothed, std::abs(smoothed.at(t, 2)(0) - truth));
    EXPECT_NEAR(smoothed.at(t)(0), std::sin(slow * t), 0.003) << t;
  }
  EXPECT_GT(worst_through, 3.0);
  EXPECT_LT(worst_smoothed, 0.05);
}

TEST(SmoothingSpline, RejectsTooFewOrUnorderedTimes) {
  EXPECT_THROW(SmoothingSpline({0.0}, Eigen::MatrixXd::Zero(1, 3)), std::invalid_argument);
  EXPECT_THROW(SmoothingSpline({0.0, 0.0}, Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
  EXPECT_THROW(SmoothingSpline({0.0, 1.0}, Eigen::MatrixXd::Zero(3, 3)), std::invalid_argument);
}
