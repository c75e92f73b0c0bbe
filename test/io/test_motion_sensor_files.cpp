#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/motion_sensor_files.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

const char* const kImuHeader = "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
const char* const kWheelHeader =
    "time,linear_x,linear_y,linear_z,angular_x,angular_y,angular_z,linear_x_variance,"
    "angular_z_variance\n";

}  // namespace

TEST(ImuCsv, ReadsCommentsHeaderAndRows) {
  const std::string text = std::string("# a simulated IMU\n\n") + kImuHeader +
                           "1.005, 0.01,-0.02,0.5, 0.1,0.2,9.81\n"
                           "1.010,0,0,0,0,0,9.8\n";
  const std::vector<ImuSample> samples = parse_imu_csv(text, "imu.csv");
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_DOUBLE_EQ(samples[0].stamp, 1.005);
  EXPECT_EQ(samples[0].angular_velocity, Eigen::Vector3d(0.01, -0.02, 0.5));
  EXPECT_EQ(samples[0].linear_acceleration, Eigen::Vector3d(0.1, 0.2, 9.81));
  EXPECT_DOUBLE_EQ(samples[1].linear_acceleration.z(), 9.8);
}

TEST(ImuCsv, KeepsTheSensorsFaultsForThePipelineToCount) {
  // nan, inf and a stamp out of order are the sensor's data, not a broken file.
  const std::string text = std::string(kImuHeader) +
                           "2.0,nan,0,0,0,0,9.8\n"
                           "1.0,0,0,0,inf,0,9.8\n";
  const std::vector<ImuSample> samples = parse_imu_csv(text, "imu.csv");
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_TRUE(std::isnan(samples[0].angular_velocity.x()));
  EXPECT_TRUE(std::isinf(samples[1].linear_acceleration.x()));
  EXPECT_GT(samples[0].stamp, samples[1].stamp);
}

TEST(ImuCsv, NamesTheLineAndWhatWasExpected) {
  EXPECT_NE(error_of([] {
              parse_imu_csv("time,gx\n", "imu.csv");
            }).find("imu.csv:1: expected the header time,gyro_x"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_imu_csv(std::string(kImuHeader) + "1,2,3\n", "imu.csv");
            }).find("imu.csv:2: expected 7 comma-separated numbers"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              parse_imu_csv(std::string(kImuHeader) + "1,2,3,x,5,6,7\n", "imu.csv");
            }).find("imu.csv:2: column 4: expected a number, found 'x'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_imu_csv("# nothing\n", "imu.csv"); }).find("imu.csv: empty"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_imu_csv(temp_path("missing_imu.csv")); }).find("cannot open"),
            std::string::npos);
}

TEST(ImuCsv, RoundTripIsExact) {
  std::vector<ImuSample> samples(3);
  for (int i = 0; i < 3; ++i) {
    samples[i].stamp = 1e9 + i / 3.0;
    samples[i].angular_velocity = Eigen::Vector3d(1.0 / 7, -std::sqrt(2.0), 1e-9 * i);
    samples[i].linear_acceleration = Eigen::Vector3d(0.1 * i, M_PI, 9.80665);
  }
  const std::string path = temp_path("round_trip_imu.csv");
  write_imu_csv(path, samples);
  const std::vector<ImuSample> read = read_imu_csv(path);
  ASSERT_EQ(read.size(), samples.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].stamp, samples[i].stamp);
    EXPECT_EQ(read[i].angular_velocity, samples[i].angular_velocity);
    EXPECT_EQ(read[i].linear_acceleration, samples[i].linear_acceleration);
  }
}

TEST(WheelOdometryCsv, ReadsAndRoundTrips) {
  const std::string text = std::string(kWheelHeader) + "0.02,10.5,0,0,0,0,0.05,0.0025,0\n";
  const std::vector<WheelOdometrySample> samples = parse_wheel_odometry_csv(text, "odom.csv");
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_DOUBLE_EQ(samples[0].linear_velocity.x(), 10.5);
  EXPECT_DOUBLE_EQ(samples[0].angular_velocity.z(), 0.05);
  EXPECT_DOUBLE_EQ(samples[0].linear_x_variance, 0.0025);
  EXPECT_DOUBLE_EQ(samples[0].angular_z_variance, 0.0);

  const std::string path = temp_path("round_trip_wheel.csv");
  write_wheel_odometry_csv(path, samples);
  const std::vector<WheelOdometrySample> read = read_wheel_odometry_csv(path);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].linear_velocity, samples[0].linear_velocity);
  EXPECT_EQ(read[0].linear_x_variance, samples[0].linear_x_variance);
  EXPECT_NE(error_of([] {
              parse_wheel_odometry_csv(kImuHeader, "odom.csv");
            }).find("odom.csv:1: expected the header time,linear_x"),
            std::string::npos);
}
