// Speed changes are smooth: continuous acceleration, bounded jerk, the distance the integral of
// the speed, and they reach the speed they aim for.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/sim/speed_profile.h"

using namespace adaptive_lego_loam::sim;

namespace {

// Largest |difference| of f between samples dt apart over [t0, t1], over dt: a bound on |f'|.
template <class F>
double steepest(F f, double t0, double t1, double dt) {
  double most = 0.0;
  for (double t = t0; t < t1; t += dt)
    most = std::max(most, std::abs(f(t + dt) - f(t)) / dt);
  return most;
}

}  // namespace

TEST(SimSpeedProfile, BrakingAndPullingAwayAreSmooth) {
  // 15 m/s, braking to 5 at 0.8 m/s^2 from t = 10 s, back to 15 at 0.6 m/s^2 after 3 s.
  SpeedProfile profile{15.0, 0.0, 20.0, 0.0, {}};
  const SpeedChange brake{10.0, -10.0, 0.8, 1.0};
  profile.changes = {brake, {brake.end_time() + 3.0, 10.0, 0.6, 1.0}};
  EXPECT_NEAR(brake.duration(), 10.0 / 0.8 + 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(profile.speed(9.0), 15.0);
  EXPECT_NEAR(profile.speed(brake.end_time() + 1.5), 5.0, 1e-9);
  EXPECT_NEAR(profile.speed(100.0), 15.0, 1e-9);
  const double end = profile.changes[1].end_time() + 5.0;
  // Speed and acceleration change continuously: no step bigger than their slopes allow.
  const double dt = 1e-3;
  EXPECT_LE(steepest([&](double t) { return profile.speed(t); }, 0.0, end, dt), 0.8 + 1e-6);
  const double jerk = steepest([&](double t) { return profile.acceleration(t); }, 0.0, end, dt);
  EXPECT_LE(jerk, 0.5 * M_PI * 0.8 / 1.0 + 1e-3);
  EXPECT_GT(jerk, 0.5 * M_PI * 0.8 / 1.0 - 1e-2);
  // The distance is the speed's integral (trapezoids at 1 ms) and the acceleration its slope.
  double integral = 0.0;
  const int steps = static_cast<int>(end / dt);
  for (int k = 0; k < steps; ++k) {
    const double t = k * dt;
    integral += 0.5 * dt * (profile.speed(t) + profile.speed(t + dt));
    const double slope = (profile.speed(t + dt) - profile.speed(t)) / dt;
    ASSERT_NEAR(slope, profile.acceleration(t + 0.5 * dt), 1e-4) << "t = " << t;
  }
  EXPECT_NEAR(profile.distance(steps * dt), integral, 1e-6);
  EXPECT_NEAR(profile.time_at_distance(profile.distance(20.0)), 20.0, 1e-6);
}

TEST(SimSpeedProfile, ASmallChangeNeverReachesTheFullAcceleration) {
  // 0.5 m/s at up to 1 m/s^2 with 1 s ramps: the ramps alone would add 1 m/s, so it peaks at 0.5.
  const SpeedChange change{0.0, 0.5, 1.0, 1.0};
  EXPECT_NEAR(change.duration(), 2.0, 1e-12);
  double peak = 0.0;
  for (double t = 0.0; t <= 2.0; t += 0.01)
    peak = std::max(peak, change.acceleration(t));
  EXPECT_NEAR(peak, 0.5, 1e-3);
  EXPECT_NEAR(change.speed(5.0), 0.5, 1e-12);
  EXPECT_NEAR(change.distance(5.0), 0.5 * 1.0 + 0.5 * 3.0, 1e-9);  // symmetric: half way in 2 s
}

TEST(SimSpeedProfile, WithoutChangesTheSlowVariationStays) {
  const SpeedProfile profile{10.0, 0.1, 20.0, 0.3, {}};
  const double omega = 2.0 * M_PI / 20.0;
  for (double t : {-0.1, 0.0, 3.7, 41.0}) {
    EXPECT_DOUBLE_EQ(profile.distance(t),
                     10.0 * (t - 0.1 / omega * (std::cos(omega * t + 0.3) - std::cos(0.3))));
    EXPECT_NEAR(profile.speed(t), 10.0 * (1.0 + 0.1 * std::sin(omega * t + 0.3)), 1e-12);
  }
  EXPECT_THROW((SpeedChange{-1.0, 1.0, 1.0, 1.0}.speed(0.0)), std::invalid_argument);
}
