#include <gtest/gtest.h>

#include <limits>

#include "adaptive_lego_loam/core/motion_sensors/motion_sensors.h"
#include "support/motion_samples.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

constexpr double kPeriod = 0.1;

// The IMU upside down, turned 90 deg and off the LiDAR's origin; the base under and behind it.
Config mounted_config() {
  Config config;
  config.imu.extrinsic_rpy_deg = {180.0, 0.0, 90.0};
  config.imu.extrinsic_xyz_m = {0.1, -0.05, -0.2};
  config.wheel_odometry.extrinsic_xyz_m = {-0.8, 0.0, -1.73};
  return config;
}

Matrix6d exact_information() {
  Matrix6d information = Matrix6d::Identity();
  information.topLeftCorner<3, 3>() *= 1e8;
  information.bottomRightCorner<3, 3>() *= 1e6;
  return information;
}

// Drives the LiDAR along `lidar` for `scans` scans from t = 0, feeding the IMU at 200 Hz (and the
// wheel at 50 Hz when asked) up to each scan, and the true motion after it. `tamper` may change
// or drop the IMU samples (returning false drops).
struct Drive {
  PoseAt lidar;
  Config config = mounted_config();
  bool wheel = false;
  std::function<bool(ImuSample&)> tamper = [](ImuSample&) { return true; };
  std::function<void(WheelOdometrySample&)> wheel_tamper = [](WheelOdometrySample&) {};
};

void drive(const Drive& d, MotionSensors& sensors, int scans,
           const std::function<void(int, const MotionPrediction&)>& check) {
  const Eigen::Isometry3d lidar_from_imu = sensors.lidar_from_imu();
  const Eigen::Isometry3d lidar_from_base = sensors.lidar_from_base();
  int imu_index = 0, wheel_index = 0;
  for (int scan = 0; scan < scans; ++scan) {
    const double stamp = scan * kPeriod;
    for (; imu_index / 200.0 <= stamp + 1e-9; ++imu_index) {
      ImuSample sample = imu_sample(d.lidar, imu_index / 200.0, lidar_from_imu);
      if (d.tamper(sample)) sensors.add_imu(sample);
    }
    for (; d.wheel && wheel_index / 50.0 <= stamp + 1e-9; ++wheel_index) {
      WheelOdometrySample sample = wheel_sample(d.lidar, wheel_index / 50.0, lidar_from_base);
      d.wheel_tamper(sample);
      sensors.add_wheel(sample);
    }
    const MotionPrediction& prediction = sensors.predict(stamp, kPeriod);
    check(scan, prediction);
    if (scan == 0) {
      sensors.update(std::nullopt, Matrix6d::Zero());
    } else {
      sensors.update(d.lidar(stamp - kPeriod).inverse() * d.lidar(stamp), exact_information());
    }
  }
}

double translation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

double rotation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return rotation_log(a.linear().transpose() * b.linear()).norm();
}

// 40 scans; from the sixth on (the filter started) each predicted motion within 1 cm of the truth.
void drive_expecting_the_true_motion(const Drive& d, MotionSensors& sensors) {
  drive(d, sensors, 40, [&](int scan, const MotionPrediction& prediction) {
    if (scan < 5) return;
    ASSERT_TRUE(prediction.motion) << scan;
    const double stamp = scan * kPeriod;
    const Eigen::Isometry3d truth = d.lidar(stamp - kPeriod).inverse() * d.lidar(stamp);
    EXPECT_LT(translation_error(prediction.motion->motion, truth), 0.01) << scan;
  });
}

}  // namespace

TEST(MotionSensors, WithoutSamplesItPredictsNothing) {
  MotionSensors sensors(mounted_config());
  EXPECT_FALSE(sensors.active());
  EXPECT_TRUE(sensors.predict(0.1, kPeriod).empty());
  sensors.update(Eigen::Isometry3d::Identity(), exact_information());
  EXPECT_TRUE(sensors.predict(0.2, kPeriod).empty());
}

TEST(MotionSensors, MountedImuPredictsTheLidarsMotionSweepAndGravity) {
  Drive d;
  d.lidar = constant_turn(12.0, 0.35);
  MotionSensors sensors(d.config);
  int predicted = 0;
  drive(d, sensors, 40, [&](int scan, const MotionPrediction& prediction) {
    // The filter starts once the LiDAR has measured three motions in a row (scans 1-3), after
    // the fourth scan.
    if (scan < 5) {
      EXPECT_FALSE(prediction.motion) << scan;
      return;
    }
    ASSERT_TRUE(prediction.motion) << scan;
    ASSERT_TRUE(prediction.sweep) << scan;
    ASSERT_TRUE(prediction.gravity) << scan;
    EXPECT_TRUE(prediction.motion->from_imu && !prediction.motion->from_wheel) << scan;
    ++predicted;
    const double stamp = scan * kPeriod;
    const Eigen::Isometry3d truth = d.lidar(stamp - kPeriod).inverse() * d.lidar(stamp);
    EXPECT_LT(translation_error(prediction.motion->motion, truth), 0.01) << scan;
    EXPECT_LT(rotation_error(prediction.motion->motion, truth), 1e-4) << scan;
    const Eigen::Isometry3d sweep_start = d.lidar(stamp).inverse() * d.lidar(stamp - kPeriod);
    EXPECT_LT(translation_error(prediction.sweep->at(0.0), sweep_start), 0.01) << scan;
    const Eigen::Isometry3d half = d.lidar(stamp).inverse() * d.lidar(stamp - 0.5 * kPeriod);
    EXPECT_LT(translation_error(prediction.sweep->at(0.5), half), 0.01) << scan;
    EXPECT_LT(std::acos(std::min(1.0, prediction.gravity->up.z())), 0.005) << scan;
  });
  EXPECT_EQ(predicted, 35);
  EXPECT_EQ(sensors.status().imu_scans, 35);
  EXPECT_TRUE(sensors.status().imu_in_use);
}

TEST(MotionSensors, WheelVelocitiesInTheImusFilterAgreeWithIt) {
  Drive d;
  d.lidar = constant_turn(12.0, 0.35);
  d.wheel = true;
  MotionSensors sensors(d.config);
  drive_expecting_the_true_motion(d, sensors);
  EXPECT_EQ(sensors.status().wheel_slips, 0);
  EXPECT_GT(sensors.status().wheel_scans, 30);
  MotionSensors again(d.config);
  int from_both = 0;
  drive(d, again, 40, [&](int, const MotionPrediction& prediction) {
    from_both += prediction.motion && prediction.motion->from_imu && prediction.motion->from_wheel;
  });
  EXPECT_GT(from_both, 30) << "the priors say both made them";
}

TEST(MotionSensors, OneWheelSpinningIsASlipByItsYawRate) {
  // From 1.5 s to 2.5 s the left wheel spins 0.3 m/s faster than the road: the odometry reports
  // half of it forward (within three of its sigmas) and a turn of 0.3 m/s over a 1.6 m track.
  Drive d;
  d.lidar = constant_turn(12.0, 0.0);
  d.wheel = true;
  d.wheel_tamper = [](WheelOdometrySample& sample) {
    if (sample.stamp < 1.5 || sample.stamp > 2.5) return;
    sample.linear_velocity.x() += 0.15;
    sample.angular_velocity.z() += 0.3 / 1.6;
  };
  MotionSensors sensors(d.config);
  drive_expecting_the_true_motion(d, sensors);
  EXPECT_GE(sensors.status().wheel_slips, 50);
}

TEST(MotionSensors, BadSamplesAreCountedAndAGapFallsBackToLidarOnlyThenRecovers) {
  Drive d;
  d.lidar = constant_turn(10.0, 0.1);
  d.tamper = [](ImuSample& sample) {
    if (std::abs(sample.stamp - 1.0) < 1e-9) sample.angular_velocity.x() = NAN;
    if (std::abs(sample.stamp - 1.5) < 1e-9) sample.linear_acceleration.z() = 1e6;
    return sample.stamp < 2.0 || sample.stamp > 4.0;  // 2 s without the IMU
  };
  MotionSensors sensors(d.config);
  std::vector<bool> predicted;
  drive(d, sensors, 80, [&](int, const MotionPrediction& prediction) {
    predicted.push_back(prediction.motion.has_value());
  });
  const MotionSensorsStatus& status = sensors.status();
  EXPECT_EQ(status.imu.faults[static_cast<int>(SampleFault::kNotFinite)], 1);
  EXPECT_EQ(status.imu.faults[static_cast<int>(SampleFault::kBeyondLimits)], 1);
  EXPECT_EQ(status.imu.gaps, 1);
  EXPECT_TRUE(predicted[19]);   // before the gap
  EXPECT_FALSE(predicted[30]);  // in it: LiDAR-only
  EXPECT_TRUE(predicted[79]);   // after it, started again
  EXPECT_GE(status.imu_fallbacks, 1);
  EXPECT_EQ(status.imu_restarts, 1);
}

TEST(MotionSensors, WheelOdometryAloneGivesTheMotionAndLearnsItsScale) {
  Drive d;
  d.lidar = constant_turn(8.0, 0.05);
  Config config = mounted_config();
  MotionSensors sensors(config);
  const Eigen::Isometry3d lidar_from_base = sensors.lidar_from_base();
  int wheel_index = 0;
  for (int scan = 0; scan < 100; ++scan) {
    const double stamp = scan * kPeriod;
    for (; wheel_index / 50.0 <= stamp + 1e-9; ++wheel_index)
      sensors.add_wheel(wheel_sample(d.lidar, wheel_index / 50.0, lidar_from_base, 1.03));
    const MotionPrediction& prediction = sensors.predict(stamp, kPeriod);
    if (scan >= 1) {
      ASSERT_TRUE(prediction.motion);
      EXPECT_FALSE(prediction.sweep);
      EXPECT_TRUE(prediction.motion->from_wheel && !prediction.motion->from_imu);
    }
    if (scan == 0) {
      sensors.update(std::nullopt, Matrix6d::Zero());
    } else {
      sensors.update(d.lidar(stamp - kPeriod).inverse() * d.lidar(stamp), exact_information());
    }
  }
  EXPECT_NEAR(sensors.status().wheel_scale, 1.0 / 1.03, 0.002);
  EXPECT_EQ(sensors.status().wheel_scans, 99);
}
