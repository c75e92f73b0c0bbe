#include "adaptive_lego_loam/core/projection/config_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace adaptive_lego_loam {
namespace {

std::string percent(int part, int whole) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f %%", 100.0 * part / std::max(whole, 1));
  return text;
}

// The angle to the nearer neighbouring beam (rad).
double row_spacing(const RangeImageGeometry& geometry, int row) {
  double spacing = INFINITY;
  if (row > 0) spacing = geometry.row_gap_rad(row, row - 1);
  if (row + 1 < geometry.rows) spacing = std::min(spacing, geometry.row_gap_rad(row, row + 1));
  return spacing;
}

}  // namespace

ConfigFit check_config_fit(const SensorParams& sensor, const RangeImage& image,
                           bool rows_from_ring) {
  ConfigFit fit;
  fit.rows_from_ring = rows_from_ring;
  fit.rows = image.rows();
  fit.columns = image.cols();
  const ProjectionStats& stats = image.stats();
  fit.projected = stats.projected;
  fit.without_cell = stats.collisions;
  fit.outside_rows = stats.outside_rows;
  const RangeImageGeometry& geometry = image.geometry();
  const double tolerance = rows_from_ring ? 0.5 : 0.2;  // of the row spacing
  std::vector<int> per_row(image.rows(), 0);
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    const int row = image.row_of(cell);
    ++per_row[row];
    const ScanPoint& p = image.point(cell);
    const double horizontal = std::hypot(p.x, p.y);
    if (horizontal < ConfigFit::kMinCheckRange || image.rows() < 2) continue;
    const double origin = sensor.beam_offsets_m.empty() ? 0.0 : sensor.beam_offsets_m[row];
    const double elevation = std::atan2(p.z - origin, horizontal);
    ++fit.checked;
    fit.off_beam += std::abs(elevation - geometry.row_elevation_rad[row]) >
                    tolerance * row_spacing(geometry, row) +
                        (rows_from_ring ? std::atan(ConfigFit::kOriginSlack / horizontal) : 0.0);
  }
  const auto first = std::find_if(per_row.begin(), per_row.end(), [](int n) { return n > 0; });
  const auto last = std::find_if(per_row.rbegin(), per_row.rend(), [](int n) { return n > 0; });
  if (first != per_row.end()) fit.empty_inner_rows = std::count(first, last.base(), 0);
  return fit;
}

std::vector<std::string> ConfigFit::problems() const {
  std::vector<std::string> out;
  if (checked >= kMinChecked && 2 * off_beam > checked) {
    out.push_back(percent(off_beam, checked) + " of the points lie farther than " +
                  (rows_from_ring ? "half" : "a fifth") + " of the row spacing " +
                  (rows_from_ring ? "(and 5 cm) " : "") + "from their row's beam (rows from the " +
                  (rows_from_ring ? "ring field" : "elevation") +
                  "): sensor.rows and the beam table (beam_angles_deg or vertical_min/max_deg, "
                  "beam_offsets_m) are not this sensor's");
  }
  if (empty_inner_rows > std::max(1, rows / 10)) {
    out.push_back(std::to_string(empty_inner_rows) + " of the " + std::to_string(rows) +
                  " rows got no point between rows that did: sensor.rows or the beam table "
                  "does not fit");
  }
  const int valid = projected + without_cell;
  if (valid > 0 && 20 * without_cell > valid) {
    out.push_back(percent(without_cell, valid) +
                  " of the points found no free column: a turn holds more returns per row than "
                  "sensor.columns = " +
                  std::to_string(columns));
  }
  if (valid > 0 && 20 * outside_rows > valid + outside_rows) {
    out.push_back(percent(outside_rows, valid + outside_rows) +
                  " of the points fall outside the rows (a ring beyond sensor.rows or "
                  "ring_to_row, or an elevation beyond the beam table)");
  }
  return out;
}

bool config_reads(const SensorParams& config, const SensorParams& sensor, int firings,
                  bool ring_field) {
  if (config.rows != sensor.rows || config.columns < firings || config.columns > 1.1 * firings ||
      std::abs(config.scan_period - sensor.scan_period) > 1e-9) {
    return false;
  }
  const bool by_ring = ring_field && config.row_source != RowSource::kElevation;
  const double angle_tolerance = by_ring ? 0.05 : 0.01;
  const auto offset = [](const SensorParams& s, int row) {
    return s.beam_offsets_m.empty() ? 0.0 : s.beam_offsets_m[row];
  };
  for (int row = 0; row < sensor.rows; ++row) {
    if (std::abs(config.beam_angles_deg[row] - sensor.beam_angles_deg[row]) > angle_tolerance) {
      return false;
    }
    if (!by_ring && std::abs(offset(config, row) - offset(sensor, row)) > 0.005) return false;
  }
  if (!by_ring) return config.row_source != RowSource::kRing;
  // The ring of each row as the sensor numbers it must come back to that row.
  const auto row_of_ring = [](const SensorParams& s, int ring) {
    if (s.ring_to_row.empty()) return ring < s.rows ? ring : -1;
    return ring < static_cast<int>(s.ring_to_row.size()) ? s.ring_to_row[ring] : -1;
  };
  for (int ring = 0; ring < std::max<int>(sensor.rows, sensor.ring_to_row.size()); ++ring) {
    const int row = row_of_ring(sensor, ring);
    if (row >= 0 && row_of_ring(config, ring) != row) return false;
  }
  return true;
}

std::optional<std::string> ConfigFitWarning::check(const SensorParams& sensor,
                                                   const RangeImage& image, bool rows_from_ring) {
  // Every scan of the first 20, then every 20th: a look at a scan costs an atan2 a point.
  if (scans_++ >= 20 && scans_ % 20 != 0) return std::nullopt;
  const std::vector<std::string> problems =
      check_config_fit(sensor, image, rows_from_ring).problems();
  for (const std::string& problem : problems) {
    // The same problem with other numbers counts once.
    const std::string kind = problem.substr(problem.find(' ') + 1);
    const bool known = std::any_of(seen_.begin(), seen_.end(), [&](const std::string& seen) {
      return seen.substr(seen.find(' ') + 1) == kind;
    });
    if (!known) seen_.push_back(problem);
  }
  if (problems.empty() || warned_) return std::nullopt;
  warned_ = true;
  std::string line = config_ + " does not fit the clouds of " + input_ + ":";
  for (const std::string& problem : problems)
    line += " " + problem + ";";
  return line +
         " measure the sensor from a recording: derive_config --input RECORDING --output "
         "my.yaml (docs/SENSORS.md)";
}

}  // namespace adaptive_lego_loam
