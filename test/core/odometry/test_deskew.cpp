// De-skewing: a sweep during which the sensor moved, each point measured from where the sensor was
// when it fired, is moved into the frame of the sweep's end.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "adaptive_lego_loam/core/odometry/deskew.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using test::Box;
using test::Scene;

namespace {

// A room with pillars, walls 10-15 m away: a sweep of it sees every azimuth.
Scene room() {
  Scene scene;
  scene.has_ground = true;
  scene.boxes = {
      {{14.0, -15.0, -2.0}, {14.5, 15.0, 4.0}}, {{-15.5, -15.0, -2.0}, {-15.0, 15.0, 4.0}},
      {{-15.0, 11.0, -2.0}, {14.0, 11.5, 4.0}}, {{-15.0, -12.5, -2.0}, {14.0, -12.0, 4.0}},
      {{4.0, 3.0, -2.0}, {4.6, 3.6, 3.0}},      {{-6.0, -5.0, -2.0}, {-5.4, -4.4, 3.0}}};
  return scene;
}

// 1.2 m forward, 0.3 m sideways and 6 deg of yaw over one sweep: a car at 12 m/s in a bend.
Eigen::Isometry3d sweep_motion() {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() =
      Eigen::AngleAxisd(6.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  motion.translation() = Eigen::Vector3d(1.2, 0.3, 0.02);
  return motion;
}

struct Sweep {
  SensorParams sensor = test::even_sensor(16, 900, -15.0, 15.0);
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d motion = sweep_motion();
  std::vector<Eigen::Vector3d> world_hits;
  Scan scan;
  Sweep() {
    start.translation() = Eigen::Vector3d(0.5, -0.4, 0.0);
    scan = test::render_sweep(sensor, room(), start, motion, world_hits);
  }
  // Each point's distance from where the straight sweep (all from its end) has it.
  std::vector<double> errors(const std::vector<ScanPoint>& points) const {
    const Eigen::Isometry3d end_from_world = (start * motion).inverse();
    std::vector<double> errors;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p(points[i].x, points[i].y, points[i].z);
      errors.push_back((p - end_from_world * world_hits[i]).norm());
    }
    return errors;
  }
};

double largest(const std::vector<double>& values) {
  double most = 0.0;
  for (double v : values)
    most = std::max(most, v);
  return most;
}

double start_azimuth(const Scan& scan) {
  return std::atan2(scan.points.front().y, scan.points.front().x);
}

}  // namespace

TEST(Deskew, TimeFieldStraightensADistortedSweep) {
  const Sweep sweep;
  ASSERT_GT(sweep.scan.points.size(), 5000u);
  std::vector<float> fractions;
  ASSERT_TRUE(sweep_fractions(sweep.scan.points, true, start_azimuth(sweep.scan),
                              sweep.sensor.scan_period, fractions));
  std::vector<ScanPoint> points = sweep.scan.points;
  EXPECT_GT(largest(sweep.errors(points)), 1.0);  // as measured, points are up to ~1 m off
  deskew_to_sweep_end(sweep.motion, fractions, points);
  EXPECT_LT(largest(sweep.errors(points)), 1e-3);
}

TEST(Deskew, AzimuthGivesTheFiringOrderWithoutATimeField) {
  const Sweep sweep;
  std::vector<float> fractions;
  // No time field: the fraction is how far the head has turned (clockwise) since the first point.
  // A point is measured in the frame the sensor had when it fired, so its azimuth is its beam's.
  EXPECT_FALSE(sweep_fractions(sweep.scan.points, false, start_azimuth(sweep.scan),
                               sweep.sensor.scan_period, fractions));
  double worst = 0.0;
  for (std::size_t i = 0; i < fractions.size(); ++i) {
    const double fired = sweep.scan.points[i].time / sweep.sensor.scan_period;
    worst = std::max(worst, std::fabs(fractions[i] - fired));
  }
  EXPECT_LT(worst, 1e-5);
  std::vector<ScanPoint> points = sweep.scan.points;
  deskew_to_sweep_end(sweep.motion, fractions, points);
  EXPECT_LT(largest(sweep.errors(points)), 1e-3);
}

TEST(Deskew, ImplausibleTimeFieldFallsBackToTheAzimuth) {
  const Sweep sweep;
  std::vector<ScanPoint> points = sweep.scan.points;
  for (ScanPoint& p : points)
    p.time *= 10.f;  // a span of ten scan periods: not seconds from the sweep's start
  std::vector<float> fractions;
  EXPECT_FALSE(sweep_fractions(points, true, start_azimuth(sweep.scan), sweep.sensor.scan_period,
                               fractions));
}

TEST(Deskew, InterpolatedMotionRunsFromIdentityToTheWholeMotion) {
  const Eigen::Isometry3d motion = sweep_motion();
  EXPECT_TRUE(interpolate_motion(motion, 0.0).isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  EXPECT_TRUE(interpolate_motion(motion, 1.0).isApprox(motion, 1e-12));
  const Eigen::Isometry3d half = interpolate_motion(motion, 0.5);
  EXPECT_TRUE((half * half).linear().isApprox(motion.linear(), 1e-12));
  EXPECT_TRUE(half.translation().isApprox(0.5 * motion.translation(), 1e-12));
}

// Each point moved by the whole pose interpolated at its fraction: what deskew_to_sweep_end must
// give, whatever shortcut it takes per point.
void expect_deskew_follows_the_interpolated_motion(const Eigen::Isometry3d& motion) {
  const Sweep sweep;
  std::vector<float> fractions(sweep.scan.points.size());
  for (std::size_t i = 0; i < fractions.size(); ++i)
    fractions[i] = static_cast<float>(i) / static_cast<float>(fractions.size());
  std::vector<ScanPoint> points = sweep.scan.points;
  deskew_to_sweep_end(motion, fractions, points);
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ScanPoint& p = sweep.scan.points[i];
    const Eigen::Vector3d expected = motion.inverse() * interpolate_motion(motion, fractions[i]) *
                                     Eigen::Vector3d(p.x, p.y, p.z);
    worst =
        std::max(worst, (Eigen::Vector3d(points[i].x, points[i].y, points[i].z) - expected).norm());
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(Deskew, EveryPointMovedAsTheInterpolatedMotionMovesIt) {
  expect_deskew_follows_the_interpolated_motion(sweep_motion());
  // A sweep turning more than half a radian (a spinning platform), and one not turning at all.
  Eigen::Isometry3d spin = sweep_motion();
  spin.linear() =
      Eigen::AngleAxisd(1.4, Eigen::Vector3d(0.2, -0.1, 1.0).normalized()).toRotationMatrix();
  expect_deskew_follows_the_interpolated_motion(spin);
  Eigen::Isometry3d straight = Eigen::Isometry3d::Identity();
  straight.translation() = Eigen::Vector3d(2.5, 0.0, 0.0);
  expect_deskew_follows_the_interpolated_motion(straight);
}

TEST(Deskew, TheSweepsFirstPointStartsItWhateverItsAzimuth) {
  for (double azimuth_deg : {-180.0, -179.99, -90.0, 0.0, 0.003, 45.0, 135.0, 179.99, 180.0}) {
    const double azimuth = azimuth_deg * M_PI / 180.0;
    ScanPoint first, later;
    first.x = static_cast<float>(20.0 * std::cos(azimuth));
    first.y = static_cast<float>(20.0 * std::sin(azimuth));
    // A quarter turn on, clockwise.
    later.x = static_cast<float>(20.0 * std::cos(azimuth - M_PI / 2));
    later.y = static_cast<float>(20.0 * std::sin(azimuth - M_PI / 2));
    // Half a degree before the start: the end of the sweep.
    ScanPoint last;
    last.x = static_cast<float>(20.0 * std::cos(azimuth + 0.5 * M_PI / 180.0));
    last.y = static_cast<float>(20.0 * std::sin(azimuth + 0.5 * M_PI / 180.0));
    std::vector<float> fractions;
    sweep_fractions({first, later, last}, false, std::atan2(first.y, first.x), 0.1, fractions);
    EXPECT_LT(fractions[0], 1e-5) << azimuth_deg;
    EXPECT_NEAR(fractions[1], 0.25, 1e-5) << azimuth_deg;
    EXPECT_NEAR(fractions[2], 1.0 - 0.5 / 360.0, 1e-5) << azimuth_deg;
  }
}

// Turning into a bend (the yaw rate rising from 0 to 40 deg/s over the sweep) with the body
// rolling 2 deg and back: no constant velocity describes it; the motion sensors' sweep does.
TEST(Deskew, AMeasuredSweepStraightensWhatAConstantVelocityCannot) {
  const auto pose_at = [](double s) {
    const double t = 0.1 * s;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const double yaw = 0.5 * (40.0 * M_PI / 180.0 / 0.1) * t * t;  // yaw rate 0 -> 40 deg/s
    const double roll = 2.0 * M_PI / 180.0 * std::sin(M_PI * s);
    pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    pose.translation() = Eigen::Vector3d(12.0 * t, 0.0, 0.0);
    return pose;
  };
  const SensorParams sensor = test::even_sensor(16, 900, -15.0, 15.0);
  std::vector<Eigen::Vector3d> world_hits;
  const Scan scan = test::render_sweep(sensor, room(), pose_at, world_hits);
  const Eigen::Isometry3d end_from_world = pose_at(1.0).inverse();
  const auto worst_error = [&](const std::vector<ScanPoint>& points) {
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p(points[i].x, points[i].y, points[i].z);
      worst = std::max(worst, (p - end_from_world * world_hits[i]).norm());
    }
    return worst;
  };
  std::vector<float> fractions;
  ASSERT_TRUE(sweep_fractions(scan.points, true, start_azimuth(scan), sensor.scan_period,
                              fractions));
  // The sweep's poses at 21 fractions, as the IMU's filter gives them.
  SweepMotion sweep;
  for (int i = 0; i <= 20; ++i)
    sweep.end_from_fraction.push_back(end_from_world * pose_at(i / 20.0));
  std::vector<ScanPoint> measured = scan.points;
  deskew_to_sweep_end(sweep, fractions, measured);
  EXPECT_LT(worst_error(measured), 0.005);  // well within a VLP-16's 2-3 cm of range noise
  // Constant velocity at the sweep's own whole motion still bends the walls by centimetres.
  std::vector<ScanPoint> constant = scan.points;
  deskew_to_sweep_end(pose_at(0.0).inverse() * pose_at(1.0), fractions, constant);
  EXPECT_GT(worst_error(constant), 0.05);
}
