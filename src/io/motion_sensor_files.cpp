#include "adaptive_lego_loam/io/motion_sensor_files.h"

#include <charconv>
#include <fstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/numeric_csv.h"

namespace adaptive_lego_loam {
namespace {

const char* const kImuHeader = "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z";
const char* const kWheelHeader =
    "time,linear_x,linear_y,linear_z,angular_x,angular_y,angular_z,linear_x_variance,"
    "angular_z_variance";

std::string format_number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

void write_rows(const std::string& path, const std::string& header,
                const std::vector<std::vector<double>>& rows) {
  std::ofstream file(path, std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  file << header << '\n';
  for (const std::vector<double>& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i)
      file << (i ? "," : "") << format_number(row[i]);
    file << '\n';
  }
  file.close();
  if (!file) throw IoError(path + ": write failed");
}

ImuSample imu_from(const std::vector<double>& row) {
  ImuSample sample;
  sample.stamp = row[0];
  sample.angular_velocity = {row[1], row[2], row[3]};
  sample.linear_acceleration = {row[4], row[5], row[6]};
  return sample;
}

WheelOdometrySample wheel_from(const std::vector<double>& row) {
  WheelOdometrySample sample;
  sample.stamp = row[0];
  sample.linear_velocity = {row[1], row[2], row[3]};
  sample.angular_velocity = {row[4], row[5], row[6]};
  sample.linear_x_variance = row[7];
  sample.angular_z_variance = row[8];
  return sample;
}

template <typename Sample, typename Convert>
std::vector<Sample> converted(const std::vector<std::vector<double>>& rows, Convert convert) {
  std::vector<Sample> samples;
  samples.reserve(rows.size());
  for (const std::vector<double>& row : rows)
    samples.push_back(convert(row));
  return samples;
}

}  // namespace

std::vector<ImuSample> read_imu_csv(const std::string& path) {
  return converted<ImuSample>(read_csv_with_header(path, kImuHeader).rows, imu_from);
}

std::vector<ImuSample> parse_imu_csv(const std::string& text, const std::string& source) {
  return converted<ImuSample>(parse_csv_with_header(text, source, kImuHeader).rows, imu_from);
}

void write_imu_csv(const std::string& path, const std::vector<ImuSample>& samples) {
  std::vector<std::vector<double>> rows;
  rows.reserve(samples.size());
  for (const ImuSample& s : samples) {
    rows.push_back({s.stamp, s.angular_velocity.x(), s.angular_velocity.y(), s.angular_velocity.z(),
                    s.linear_acceleration.x(), s.linear_acceleration.y(),
                    s.linear_acceleration.z()});
  }
  write_rows(path, kImuHeader, rows);
}

std::vector<WheelOdometrySample> read_wheel_odometry_csv(const std::string& path) {
  return converted<WheelOdometrySample>(read_csv_with_header(path, kWheelHeader).rows, wheel_from);
}

std::vector<WheelOdometrySample> parse_wheel_odometry_csv(const std::string& text,
                                                          const std::string& source) {
  return converted<WheelOdometrySample>(parse_csv_with_header(text, source, kWheelHeader).rows,
                                        wheel_from);
}

void write_wheel_odometry_csv(const std::string& path,
                              const std::vector<WheelOdometrySample>& samples) {
  std::vector<std::vector<double>> rows;
  rows.reserve(samples.size());
  for (const WheelOdometrySample& s : samples) {
    rows.push_back({s.stamp, s.linear_velocity.x(), s.linear_velocity.y(), s.linear_velocity.z(),
                    s.angular_velocity.x(), s.angular_velocity.y(), s.angular_velocity.z(),
                    s.linear_x_variance, s.angular_z_variance});
  }
  write_rows(path, kWheelHeader, rows);
}

}  // namespace adaptive_lego_loam
