#pragma once
// The motion sensors' CSV files, which run_sequence reads (--imu, --wheel-odom) and lidar_sim
// writes (imu.csv, wheel_odom.csv in a sequence folder):
//
//   imu.csv         time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z
//                   s; rad/s; m/s^2 (specific force: +g up at rest); IMU frame
//   wheel_odom.csv  time,linear_x,linear_y,linear_z,angular_x,angular_y,angular_z,
//                   linear_x_variance,angular_z_variance
//                   s; m/s; rad/s; (m/s)^2; (rad/s)^2 (0: not reported); the base frame's twist
//
// Times are on the scans' clock (a KITTI folder's times.txt, a bag's header stamps). Lines
// starting with '#' and blank lines are skipped; the first other line is the header above.
// Values may be nan or inf and samples out of order: that is the sensor's data, which the
// pipeline checks, counts and drops (core/motion_sensors/). A line that is not the expected
// count of numbers throws IoError as "<path>:<line>: <what was expected>". Writers print every
// number in its shortest exact form, so a round trip is exact.

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam {

std::vector<ImuSample> read_imu_csv(const std::string& path);
std::vector<ImuSample> parse_imu_csv(const std::string& text, const std::string& source);
void write_imu_csv(const std::string& path, const std::vector<ImuSample>& samples);

std::vector<WheelOdometrySample> read_wheel_odometry_csv(const std::string& path);
std::vector<WheelOdometrySample> parse_wheel_odometry_csv(const std::string& text,
                                                          const std::string& source);
void write_wheel_odometry_csv(const std::string& path,
                              const std::vector<WheelOdometrySample>& samples);

}  // namespace adaptive_lego_loam
