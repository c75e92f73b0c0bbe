// Measures an unknown spinning LiDAR from a few of its scans (a bag topic, a folder of PCD or .bin
// files) and writes a starting config: its sensor section from the measurements (rows, beams,
// origins, ring numbering, columns, ranges, ground rows, scan period, de-skewing), the stages'
// parameters of the shipped config with as many beams, and the report as comments.

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/sensor_survey.h"
#include "adaptive_lego_loam/io/atomic_files.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_sequence.h"
#include "adaptive_lego_loam/ros/bag_sequence.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;
namespace fs = std::filesystem;

namespace {

struct Options {
  std::string input, topic, output, name;
  int scans = 20;
};

std::vector<Scan> read_scans(const Options& o, std::string& description) {
  std::unique_ptr<ScanSequence> sequence;
  if (fs::is_directory(o.input)) {
    sequence = open_folder_sequence(o.input);
  } else if (fs::path(o.input).extension() == ".bag") {
    sequence = ros_bridge::open_bag_sequence(o.input, o.topic);
  } else {
    throw IoError(o.input + ": expected a bag, a KITTI sequence folder or a folder of .pcd/.bin");
  }
  description = sequence->describe();
  std::vector<Scan> scans;
  while (static_cast<int>(scans.size()) < o.scans) {
    std::optional<Scan> scan = sequence->next();
    if (!scan) break;
    scans.push_back(std::move(*scan));
  }
  if (scans.empty()) throw IoError(o.input + ": no scans");
  // A folder without times.txt gives its scans made-up stamps: the period is not in them.
  if (fs::is_directory(o.input) && !folder_has_times(o.input)) {
    for (Scan& scan : scans)
      scan.stamp = 0.0;
  }
  return scans;
}

// The shipped config whose stages' parameters a sensor of `rows` beams starts from.
std::string base_config(int rows) {
  const char* name = rows <= 16 ? "vlp16.yaml" : rows <= 32 ? "hdl32.yaml" : "hdl64e.yaml";
  return std::string(CONFIG_DIR) + "/" + name;
}

std::string list(const std::vector<double>& values, const char* format) {
  std::string text = "[";
  char number[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(number, sizeof(number), format, values[i]);
    text += (i ? ", " : "") + std::string(number);
  }
  return text + "]";
}

// Beams evenly spaced to within a thousandth of a degree: their limits say it as well.
bool evenly_spaced(const std::vector<double>& angles) {
  const double gap = (angles.back() - angles.front()) / (angles.size() - 1);
  for (std::size_t row = 1; row < angles.size(); ++row)
    if (std::abs(angles[row] - angles[row - 1] - gap) > 1e-3) return false;
  return true;
}

double smallest_gap(const std::vector<double>& angles) {
  double gap = INFINITY;
  for (std::size_t row = 1; row < angles.size(); ++row)
    gap = std::min(gap, angles[row] - angles[row - 1]);
  return gap;
}

std::string sensor_section(const SensorParams& s) {
  std::ostringstream out;
  char line[160];
  out << "sensor:\n  name: " << s.name << "\n  rows: " << s.rows << "\n  columns: " << s.columns
      << "                   # firings a turn\n  row_source: auto\n";
  if (evenly_spaced(s.beam_angles_deg)) {
    std::snprintf(line, sizeof(line), "  vertical_min_deg: %.4f\n  vertical_max_deg: %.4f\n",
                  s.beam_angles_deg.front(), s.beam_angles_deg.back());
    out << line;
  } else {
    out << "  beam_angles_deg: " << list(s.beam_angles_deg, "%.4f") << "\n";
  }
  if (!s.beam_offsets_m.empty()) {
    out << "  beam_offsets_m: " << list(s.beam_offsets_m, "%.4f") << "\n";
  }
  if (!s.ring_to_row.empty()) {
    out << "  ring_to_row: [";
    for (std::size_t i = 0; i < s.ring_to_row.size(); ++i)
      out << (i ? ", " : "") << s.ring_to_row[i];
    out << "]\n";
  }
  std::snprintf(line, sizeof(line),
                "  min_range: %.1f\n  max_range: %.1f\n  mount_angle_deg: 0.0\n"
                "  ground_rows: %d                 # beams at or below -1 deg\n"
                "  scan_period: %.4f\n  deskewed: %s\n",
                s.min_range, s.max_range, s.ground_rows, s.scan_period,
                s.deskewed ? "true" : "false");
  out << line;
  return out.str();
}

// The base's sections after `sensor`, with ground removal pairing rows 1 deg apart for beams
// closer than that (as the shipped configs of such sensors do).
std::string stage_sections(const std::string& base_path, const SensorParams& sensor) {
  std::ifstream file(base_path);
  std::stringstream text;
  text << file.rdbuf();
  std::string body = text.str();
  const std::size_t start = body.find("\nsegmentation:");
  if (!file || start == std::string::npos) {
    throw IoError(base_path + ": expected a config with a segmentation section");
  }
  body = body.substr(start);
  const std::string tolerance = "  ground_slope_tolerance_deg: 10.0\n";
  const std::size_t at = body.find(tolerance);
  if (smallest_gap(sensor.beam_angles_deg) < 1.0 && at != std::string::npos &&
      body.find("ground_row_gap_deg") == std::string::npos) {
    body.insert(at + tolerance.size(),
                "  ground_row_gap_deg: 1.0         # pairs rows at least 1 deg apart\n");
  }
  return body;
}

std::string comment(const std::string& text) {
  std::string out, line = "#";
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    if (line.size() + 1 + word.size() > 99) {
      out += line + "\n";
      line = "#  ";
    }
    line += " " + word;
  }
  return out + line + "\n";
}

int run(Options& o) {
  std::string description;
  const std::vector<Scan> scans = read_scans(o, description);
  const SensorSurvey survey = survey_sensor(scans);
  if (!survey.not_spinning.empty()) {
    throw std::runtime_error(o.input + ": not a spinning LiDAR: " + survey.not_spinning);
  }
  if (o.name.empty()) o.name = fs::path(o.output).stem().string();
  const SensorParams sensor = surveyed_sensor(survey, o.name);
  const std::string base = base_config(sensor.rows);
  std::string text =
      comment("Derived by derive_config from " + description + ", " + std::to_string(survey.scans) +
              " scans: a starting point to check "
              "(docs/SENSORS.md). The stages' parameters are " +
              fs::path(base).filename().string() + "'s.");
  std::printf("derive_config: %s, %d scans\n", description.c_str(), survey.scans);
  for (const std::string& line : survey.report) {
    text += comment(line);
    std::printf("  %s\n", line.c_str());
  }
  text += sensor_section(sensor) + stage_sections(base, sensor);
  parse_config(text, o.output);  // what is written must load
  write_atomically(o.output, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out << text;
    if (!out) throw IoError(o.output + ": cannot write");
  });
  std::printf("derive_config: wrote %s (stages from %s)\n", o.output.c_str(),
              fs::path(base).filename().string().c_str());
  return tools::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Measure a spinning LiDAR from a few of its scans and write a starting config: rows (from "
      "the ring field, the points' order or their elevations), beams and their origins, columns, "
      "ranges, ground rows, scan period and whether the sweep is de-skewed, with a report."};
  Options o;
  app.add_option("--input", o.input, "a bag, a KITTI sequence folder or a folder of .pcd/.bin")
      ->required();
  app.add_option("--topic", o.topic, "the bag's PointCloud2 topic (default: its only one)");
  app.add_option("--output", o.output, "the config to write (YAML)")->required();
  app.add_option("--scans", o.scans, "scans to read from the start (default 20)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--name", o.name, "sensor.name (default: the output's file name)");
  if (const auto status = tools::parse_command_line(app, argc, argv, "derive_config")) {
    return *status;
  }
  return tools::run_job("derive_config", [&] { return run(o); });
}
