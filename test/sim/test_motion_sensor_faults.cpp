// Fault specs parse or fail with a message naming the item; each fault does to the samples what
// the spec says.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/sim/motion_sensor_faults.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

std::vector<ImuSample> imu_at_100hz(double seconds) {
  std::vector<ImuSample> samples;
  for (int k = 0; k <= static_cast<int>(std::lround(seconds * 100.0)); ++k) {
    ImuSample s;
    s.stamp = 0.01 * k;
    s.linear_acceleration.z() = 9.81;
    samples.push_back(s);
  }
  return samples;
}

std::string error_of(const std::string& spec) {
  try {
    parse_faults(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MotionSensorFaults, ParsesSpecsAndNamesABadItem) {
  const std::vector<SensorFault> faults = parse_faults("imu:nan@3,wheel:absurd@4.5");
  ASSERT_EQ(faults.size(), 2u);
  EXPECT_TRUE(faults[0].imu);
  EXPECT_EQ(faults[0].kind, FaultKind::kNan);
  EXPECT_FALSE(faults[1].imu);
  EXPECT_EQ(faults[1].kind, FaultKind::kAbsurd);
  EXPECT_DOUBLE_EQ(faults[1].time, 4.5);
  EXPECT_EQ(fault_name(faults[1]), "wheel:absurd@4.5");
  for (const std::string bad : {"imu:nan", "gps:nan@3", "imu:melt@3", "imu:gap@soon", "imu:gap@"}) {
    const std::string message = error_of("imu:nan@1," + bad);
    EXPECT_NE(message.find("'" + bad + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("SENSOR:KIND@TIME"), std::string::npos) << message;
  }
}

TEST(MotionSensorFaults, EachFaultChangesTheSamplesAsDocumented) {
  std::vector<ImuSample> samples = imu_at_100hz(10.0);
  const std::size_t count = samples.size();
  apply_faults(parse_faults("imu:nan@1,imu:repeat@2,imu:disorder@3,imu:absurd@4,wheel:nan@5"),
               samples);
  EXPECT_TRUE(std::isnan(samples[100].angular_velocity.x()));
  EXPECT_TRUE(std::isnan(samples[100].linear_acceleration.z()));
  EXPECT_EQ(samples[200].stamp, samples[199].stamp);
  EXPECT_GT(samples[300].stamp, samples[301].stamp);
  EXPECT_EQ(samples[400].linear_acceleration.x(), 500.0);
  EXPECT_EQ(samples.size(), count);
  EXPECT_FALSE(std::isnan(samples[500].angular_velocity.x()));  // a wheel fault

  std::vector<ImuSample> gap = imu_at_100hz(10.0);
  apply_faults(parse_faults("imu:gap@2,imu:rate_drop@6"), gap);
  int in_gap = 0, in_drop = 0;
  for (const ImuSample& s : gap) {
    in_gap += s.stamp >= 2.0 - 1e-9 && s.stamp < 4.0 - 1e-9;
    in_drop += s.stamp >= 6.0 - 1e-9 && s.stamp < 8.0 - 1e-9;
  }
  EXPECT_EQ(in_gap, 0);
  EXPECT_EQ(in_drop, 50);  // 200 samples at a quarter of the rate
}

TEST(MotionSensorFaults, AnAbsurdWheelSpeed) {
  std::vector<WheelOdometrySample> samples(100);
  for (std::size_t k = 0; k < samples.size(); ++k)
    samples[k].stamp = 0.02 * k;
  apply_faults(parse_faults("wheel:absurd@1"), samples);
  EXPECT_EQ(samples[50].linear_velocity.x(), 300.0);
  EXPECT_EQ(samples[49].linear_velocity.x(), 0.0);
}
