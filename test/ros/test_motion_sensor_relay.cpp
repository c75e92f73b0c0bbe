// feature_association's hand-over of the motion sensors' samples: when a scan is held, and that
// the graph's predictions equal those of samples handed over as run_sequence hands them over.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/ros/motion_sensor_relay.h"
#include "support/motion_samples.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;
using adaptive_lego_loam::test::PoseAt;

namespace {

constexpr double kPeriod = 0.1;
constexpr double kTimeout = 0.2;
constexpr int kScans = 12;

Config mounted_config() {
  Config config;
  config.imu.extrinsic_rpy_deg = {180.0, 2.5, 90.0};
  config.imu.extrinsic_xyz_m = {-0.12, 0.08, -0.18};
  config.wheel_odometry.extrinsic_xyz_m = {0.0, 0.0, -1.73};
  return config;
}

Matrix6d lidar_information() {
  Matrix6d information = Matrix6d::Identity();
  information.topLeftCorner<3, 3>() *= 1e8;
  information.bottomRightCorner<3, 3>() *= 1e6;
  return information;
}

ImuSample imu_at(double t) {
  static const PoseAt drive = adaptive_lego_loam::test::constant_turn(8.0, 0.2);
  static const Eigen::Isometry3d lidar_from_imu = pose_from_rpy_xyz(
      mounted_config().imu.extrinsic_rpy_deg.data(), mounted_config().imu.extrinsic_xyz_m.data());
  return adaptive_lego_loam::test::imu_sample(drive, t, lidar_from_imu);
}

WheelOdometrySample wheel_at(double t) {
  static const PoseAt drive = adaptive_lego_loam::test::constant_turn(8.0, 0.2);
  Eigen::Isometry3d lidar_from_base = Eigen::Isometry3d::Identity();
  lidar_from_base.translation().z() = -1.73;
  return adaptive_lego_loam::test::wheel_sample(drive, t, lidar_from_base);
}

// The drive's samples in the order they arrive, with the faults a sensor may have: a NaN, a
// repeated stamp, and two samples swapped across a scan's stamp (0.505 before 0.495).
std::vector<ImuSample> arriving_imu() {
  std::vector<ImuSample> samples;
  for (int i = 0; i * 0.005 <= kScans * kPeriod + 0.05; ++i)
    samples.push_back(imu_at(i * 0.005));
  samples[40].angular_velocity.x() = std::numeric_limits<double>::quiet_NaN();
  samples[61].stamp = samples[60].stamp;
  std::swap(samples[99], samples[101]);
  return samples;
}

std::vector<WheelOdometrySample> arriving_wheel() {
  std::vector<WheelOdometrySample> samples;
  for (int i = 0; i * 0.02 <= kScans * kPeriod + 0.05; ++i)
    samples.push_back(wheel_at(i * 0.02));
  samples[10].linear_velocity.x() = 300.0;  // beyond any vehicle, at 0.2 s
  return samples;
}

// The true motion between scans, as mapping would report it.
Eigen::Isometry3d mapped_motion(int scan) {
  static const PoseAt drive = adaptive_lego_loam::test::constant_turn(8.0, 0.2);
  return drive((scan - 1) * kPeriod).inverse() * drive(scan * kPeriod);
}

std::optional<Eigen::Isometry3d> scan_motion(int scan) {
  if (scan == 0) return std::nullopt;
  return mapped_motion(scan);
}

// Each scan's predicted motion (identity when none).
using Predictions = std::vector<std::optional<Eigen::Isometry3d>>;

std::optional<Eigen::Isometry3d> motion_of(const MotionPrediction* prediction) {
  if (!prediction || !prediction->motion) return std::nullopt;
  return prediction->motion->motion;
}

// As run_sequence: each input's samples in their order up to each scan's stamp, then the scan,
// then its mapped motion (none for `unmapped`).
Predictions offline(int unmapped = -1) {
  MotionSensors sensors(mounted_config());
  const std::vector<ImuSample> imu = arriving_imu();
  const std::vector<WheelOdometrySample> wheel = arriving_wheel();
  std::size_t next_imu = 0, next_wheel = 0;
  Predictions predictions;
  for (int scan = 0; scan < kScans; ++scan) {
    const double stamp = scan * kPeriod;
    for (; next_imu < imu.size() && imu[next_imu].stamp <= stamp; ++next_imu)
      sensors.add_imu(imu[next_imu]);
    for (; next_wheel < wheel.size() && wheel[next_wheel].stamp <= stamp; ++next_wheel)
      sensors.add_wheel(wheel[next_wheel]);
    const MotionPrediction& prediction = sensors.predict(stamp, kPeriod);
    predictions.push_back(motion_of(prediction.empty() ? nullptr : &prediction));
    if (scan == unmapped) {
      sensors.update(std::nullopt, Matrix6d::Zero());
    } else {
      sensors.update(scan_motion(scan), scan == 0 ? Matrix6d::Zero() : lidar_information());
    }
  }
  return predictions;
}

void expect_same(const Predictions& graph, const Predictions& reference) {
  ASSERT_EQ(graph.size(), reference.size());
  int predicted = 0;
  for (std::size_t i = 0; i < graph.size(); ++i) {
    ASSERT_EQ(graph[i].has_value(), reference[i].has_value()) << "scan " << i;
    if (!graph[i]) continue;
    ++predicted;
    EXPECT_TRUE(graph[i]->isApprox(*reference[i], 0.0)) << "scan " << i;  // bit for bit
  }
  EXPECT_GT(predicted, kScans / 2) << "the filter should have started";
}

MotionSensorInputs both() {
  return {true, true};
}

}  // namespace

TEST(MotionSensorRelay, AScanWaitsForASampleAtOrAfterItsStamp) {
  MotionSensorRelay relay(mounted_config(), {true, false}, kTimeout);
  for (int i = 0; i < 20; ++i)
    relay.add_imu(imu_at(i * 0.005), 0.0);  // up to 0.095 s
  EXPECT_EQ(relay.release(0.1, 0.0, 0.01), ScanRelease::kWait);
  relay.add_imu(imu_at(0.1), 0.02);
  EXPECT_EQ(relay.release(0.1, 0.0, 0.02), ScanRelease::kReady);
}

TEST(MotionSensorRelay, AnInputThatNeverSentIsNotWaitedFor) {
  MotionSensorRelay relay(mounted_config(), both(), kTimeout);
  EXPECT_EQ(relay.release(0.1, 0.0, 0.0), ScanRelease::kReady);
  relay.add_wheel(wheel_at(0.1), 0.0);
  EXPECT_EQ(relay.release(0.1, 0.0, 0.0), ScanRelease::kReady);
}

TEST(MotionSensorRelay, ASilentInputHoldsOneScanUntilTheTimeoutNotEach) {
  MotionSensorRelay relay(mounted_config(), {true, false}, kTimeout);
  relay.add_imu(imu_at(0.05), 1.0);
  // The IMU stopped at 0.05 s: the scan at 0.1 s waits while a sample may still come.
  EXPECT_EQ(relay.release(0.1, 1.0, 1.1), ScanRelease::kWait);
  EXPECT_EQ(relay.release(0.1, 1.0, 1.25), ScanRelease::kTimeout);
  // Later scans of the gap go on at once: the IMU has been silent that long.
  EXPECT_EQ(relay.release(0.2, 1.3, 1.3), ScanRelease::kTimeout);
  // It is back: a scan waits for it again.
  relay.add_imu(imu_at(0.3), 1.4);
  EXPECT_EQ(relay.release(0.4, 1.45, 1.5), ScanRelease::kWait);
}

TEST(MotionSensorRelay, SamplesThatLagHoldAScanOnlyUntilTheTimeout) {
  MotionSensorRelay relay(mounted_config(), {true, false}, kTimeout);
  for (int i = 0; i < 10; ++i) {
    relay.add_imu(imu_at(i * 0.005), 0.05 * i);  // arriving, but far behind the scan
    EXPECT_EQ(relay.release(1.0, 0.0, 0.05 * i),
              0.05 * i < kTimeout ? ScanRelease::kWait : ScanRelease::kTimeout)
        << i;
  }
}

TEST(MotionSensorRelay, TheNextScanWaitsForThePreviousOnesFeedback) {
  MotionSensorRelay relay(mounted_config(), {true, false}, kTimeout);
  for (int i = 0; i <= 60; ++i)
    relay.add_imu(imu_at(i * 0.005), 0.0);
  relay.predict(0.1, kPeriod, ScanRelease::kReady, 1.0);
  EXPECT_EQ(relay.release(0.2, 0.5, 1.05), ScanRelease::kWait);
  relay.add_feedback(0.1, std::nullopt, Matrix6d::Zero());
  EXPECT_EQ(relay.release(0.2, 0.5, 1.05), ScanRelease::kReady);
  // Without it, the wait is counted from the prediction, not from when the scan was complete.
  relay.predict(0.2, kPeriod, ScanRelease::kReady, 2.0);
  EXPECT_EQ(relay.release(0.3, 0.0, 2.1), ScanRelease::kWait);
  EXPECT_EQ(relay.release(0.3, 0.0, 2.25), ScanRelease::kTimeout);
  relay.predict(0.3, kPeriod, ScanRelease::kTimeout, 2.25);
  EXPECT_EQ(relay.missed_feedback(), 1);
  EXPECT_EQ(relay.timeouts(), 1);
  relay.add_feedback(0.2, std::nullopt, Matrix6d::Zero());  // too late: ignored
  EXPECT_EQ(relay.late_feedback(), 1);
}

TEST(MotionSensorRelay, PredictsAsSamplesHandedOverUpToEachScanInTheirOrder) {
  // Every sample arrived before the first scan is processed (a fast sensor, a slow LiDAR
  // stage): only those up to each scan's stamp are handed over for it, as offline.
  MotionSensorRelay relay(mounted_config(), both(), kTimeout);
  for (const ImuSample& sample : arriving_imu())
    relay.add_imu(sample, 0.0);
  for (const WheelOdometrySample& sample : arriving_wheel())
    relay.add_wheel(sample, 0.0);
  Predictions predictions;
  for (int scan = 0; scan < kScans; ++scan) {
    const double stamp = scan * kPeriod;
    ASSERT_EQ(relay.release(stamp, 0.0, 0.0), ScanRelease::kReady) << scan;
    predictions.push_back(motion_of(relay.predict(stamp, kPeriod, ScanRelease::kReady, 0.0)));
    relay.add_feedback(stamp, scan_motion(scan),
                       scan == 0 ? Matrix6d::Zero() : lidar_information());
  }
  expect_same(predictions, offline());
}

TEST(MotionSensorRelay, SamplesArrivingInStepGiveTheSamePredictions) {
  // Each scan's samples arrive just before it and the next ones just after it, as in a drive.
  MotionSensorRelay relay(mounted_config(), both(), kTimeout);
  const std::vector<ImuSample> imu = arriving_imu();
  const std::vector<WheelOdometrySample> wheel = arriving_wheel();
  std::size_t next_imu = 0, next_wheel = 0;
  Predictions predictions;
  for (int scan = 0; scan < kScans; ++scan) {
    const double stamp = scan * kPeriod;
    for (; next_imu < imu.size() && imu[next_imu].stamp <= stamp + 0.01; ++next_imu)
      relay.add_imu(imu[next_imu], 0.0);
    for (; next_wheel < wheel.size() && wheel[next_wheel].stamp <= stamp + 0.03; ++next_wheel)
      relay.add_wheel(wheel[next_wheel], 0.0);
    predictions.push_back(motion_of(relay.predict(stamp, kPeriod, ScanRelease::kReady, 0.0)));
    relay.add_feedback(stamp, scan_motion(scan),
                       scan == 0 ? Matrix6d::Zero() : lidar_information());
  }
  expect_same(predictions, offline());
}

TEST(MotionSensorRelay, AFeedbackThatNeverCameIsAScanNotMapped) {
  MotionSensorRelay relay(mounted_config(), both(), kTimeout);
  for (const ImuSample& sample : arriving_imu())
    relay.add_imu(sample, 0.0);
  for (const WheelOdometrySample& sample : arriving_wheel())
    relay.add_wheel(sample, 0.0);
  constexpr int kLost = 6;
  Predictions predictions;
  for (int scan = 0; scan < kScans; ++scan) {
    const double stamp = scan * kPeriod;
    predictions.push_back(motion_of(relay.predict(stamp, kPeriod, ScanRelease::kReady, 0.0)));
    if (scan == kLost) continue;
    relay.add_feedback(stamp, scan_motion(scan),
                       scan == 0 ? Matrix6d::Zero() : lidar_information());
  }
  EXPECT_EQ(relay.missed_feedback(), 1);
  expect_same(predictions, offline(kLost));
}

TEST(MotionSensorRelay, EachInputsFirstFaultOfAKindIsReportedForTheLog) {
  MotionSensorRelay relay(mounted_config(), both(), kTimeout);
  for (const ImuSample& sample : arriving_imu())
    relay.add_imu(sample, 0.0);
  for (const WheelOdometrySample& sample : arriving_wheel())
    relay.add_wheel(sample, 0.0);
  relay.predict(0.3, kPeriod, ScanRelease::kReady, 0.0);
  std::vector<SampleFaultReport> faults = relay.take_faults();
  ASSERT_EQ(faults.size(), 3u);  // the NaN, the repeated stamp (IMU) and the absurd speed
  EXPECT_EQ(faults[0].input, "IMU");
  EXPECT_EQ(faults[0].fault, SampleFault::kNotFinite);
  EXPECT_TRUE(faults[0].first);
  EXPECT_EQ(faults[0].describe(), "IMU sample at 0.200000 s dropped: not finite");
  EXPECT_EQ(faults[1].fault, SampleFault::kRepeatedStamp);
  EXPECT_EQ(faults[2].input, "wheel odometry");
  EXPECT_EQ(faults[2].fault, SampleFault::kBeyondLimits);
  EXPECT_TRUE(relay.take_faults().empty());
}

TEST(MotionSensorRelay, TheSecondFaultOfAKindIsCountedNotLogged) {
  MotionSensorRelay relay(mounted_config(), {true, false}, kTimeout);
  for (int i = 0; i < 4; ++i) {
    ImuSample sample = imu_at(i * 0.005);
    if (i == 1 || i == 2) sample.linear_acceleration.z() = std::numeric_limits<double>::infinity();
    relay.add_imu(sample, 0.0);
  }
  relay.predict(0.02, kPeriod, ScanRelease::kReady, 0.0);
  const std::vector<SampleFaultReport> faults = relay.take_faults();
  ASSERT_EQ(faults.size(), 2u);
  EXPECT_TRUE(faults[0].first);
  EXPECT_FALSE(faults[1].first);
  EXPECT_EQ(relay.sensors()->status().imu.faults[static_cast<int>(SampleFault::kNotFinite)], 2);
}

TEST(MotionSensorRelay, TimeGoingBackEmptiesTheInputsQueue) {
  MotionSensorRelay relay(mounted_config(), {true, false}, kTimeout);
  relay.add_imu(imu_at(10.0), 0.0);
  relay.add_imu(imu_at(10.005), 0.0);
  relay.add_imu(imu_at(10.001), 0.0);  // out of order, not time going back
  EXPECT_EQ(relay.queued(), 3);
  relay.add_imu(imu_at(2.0), 0.0);
  EXPECT_EQ(relay.queued(), 1);
  EXPECT_EQ(relay.release(2.0, 0.0, 0.0), ScanRelease::kReady);
}

TEST(MotionSensorRelay, TfExtrinsicsReplaceTheConfigs) {
  MotionSensorRelay relay(mounted_config(), both(), kTimeout);
  Eigen::Isometry3d lidar_from_imu = Eigen::Isometry3d::Identity();
  lidar_from_imu.linear() = rotation_exp(Eigen::Vector3d(0.1, -0.2, 1.5));
  lidar_from_imu.translation() = Eigen::Vector3d(0.3, -0.1, 0.05);
  Eigen::Isometry3d lidar_from_base = Eigen::Isometry3d::Identity();
  lidar_from_base.translation() = Eigen::Vector3d(-0.5, 0.0, -1.2);
  relay.set_lidar_from_imu(lidar_from_imu);
  relay.set_lidar_from_base(lidar_from_base);
  relay.predict(0.1, kPeriod, ScanRelease::kReady, 0.0);
  ASSERT_TRUE(relay.sensors());
  EXPECT_TRUE(relay.sensors()->lidar_from_imu().isApprox(lidar_from_imu, 1e-12));
  EXPECT_TRUE(relay.sensors()->lidar_from_base().isApprox(lidar_from_base, 1e-12));
}

TEST(Extrinsic, AsTheConfigsAnglesItGivesThePoseBack) {
  const std::vector<std::vector<double>> rpy_deg = {{180.0, 2.5, 90.0},     {0.0, 0.0, 0.0},
                                                    {-30.0, 89.9999, 10.0}, {10.0, 90.0, -20.0},
                                                    {45.0, -90.0, 0.0},     {-170.0, -45.0, 135.0}};
  for (const std::vector<double>& angles : rpy_deg) {
    const std::vector<double> xyz = {-0.12, 0.08, -0.18};
    const Eigen::Isometry3d pose = pose_from_rpy_xyz(angles.data(), xyz.data());
    std::vector<double> rpy_back, xyz_back;
    set_extrinsic(pose, rpy_back, xyz_back);
    ASSERT_EQ(rpy_back.size(), 3u);
    EXPECT_EQ(xyz_back, xyz);
    const Eigen::Isometry3d back = pose_from_rpy_xyz(rpy_back.data(), xyz_back.data());
    EXPECT_LT((back.linear() - pose.linear()).norm(), 1e-12)
        << angles[0] << " " << angles[1] << " " << angles[2];
    for (double angle : rpy_back) {
      EXPECT_LE(std::fabs(angle), 180.0);  // within the config's range
    }
  }
}
