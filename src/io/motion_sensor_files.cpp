#include "adaptive_lego_loam/io/motion_sensor_files.h"

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

const char* const kImuHeader = "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z";
const char* const kWheelHeader =
    "time,linear_x,linear_y,linear_z,angular_x,angular_y,angular_z,linear_x_variance,"
    "angular_z_variance";

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::size_t column_count(const std::string& header) {
  std::size_t count = 1;
  for (char c : header)
    count += c == ',';
  return count;
}

// The rows of numbers under `header`, each of the header's column count. nan and inf are read as
// such: they are the sensor's, and the pipeline counts them.
std::vector<std::vector<double>> parse_rows(std::istream& input, const std::string& source,
                                            const std::string& header) {
  const std::size_t columns = column_count(header);
  std::vector<std::vector<double>> rows;
  bool header_seen = false;
  std::string line;
  for (int number = 1; std::getline(input, line); ++number) {
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#') continue;
    const std::string place = source + ":" + std::to_string(number);
    if (!header_seen) {
      std::string spaceless;
      for (char c : text)
        if (c != ' ' && c != '\t') spaceless += c;
      if (spaceless != header) throw IoError(place + ": expected the header " + header);
      header_seen = true;
      continue;
    }
    std::vector<double>& row = rows.emplace_back();
    std::istringstream cells(text);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      const std::string value = trimmed(cell);
      char* end = nullptr;
      const double parsed = std::strtod(value.c_str(), &end);
      if (value.empty() || end != value.c_str() + value.size()) {
        throw IoError(place + ": column " + std::to_string(row.size() + 1) +
                      ": expected a number, found '" + value + "'");
      }
      row.push_back(parsed);
    }
    if (row.size() != columns) {
      throw IoError(place + ": expected " + std::to_string(columns) + " comma-separated numbers (" +
                    header + "), found " + std::to_string(row.size()));
    }
  }
  if (input.bad()) throw IoError(source + ": read failed");
  if (!header_seen) throw IoError(source + ": empty: expected the header " + header);
  return rows;
}

std::vector<std::vector<double>> read_rows(const std::string& path, const std::string& header) {
  std::ifstream file(path);
  if (!file) throw IoError(path + ": cannot open");
  return parse_rows(file, path, header);
}

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
  return converted<ImuSample>(read_rows(path, kImuHeader), imu_from);
}

std::vector<ImuSample> parse_imu_csv(const std::string& text, const std::string& source) {
  std::istringstream input(text);
  return converted<ImuSample>(parse_rows(input, source, kImuHeader), imu_from);
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
  return converted<WheelOdometrySample>(read_rows(path, kWheelHeader), wheel_from);
}

std::vector<WheelOdometrySample> parse_wheel_odometry_csv(const std::string& text,
                                                          const std::string& source) {
  std::istringstream input(text);
  return converted<WheelOdometrySample>(parse_rows(input, source, kWheelHeader), wheel_from);
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
