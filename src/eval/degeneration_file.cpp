#include "adaptive_lego_loam/eval/degeneration_file.h"

#include <cmath>

#include "adaptive_lego_loam/io/numeric_csv.h"
#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

// The columns found in the header (-1: missing).
struct Columns {
  int frame = -1, degenerate = -1, matched = -1, covariance = -1;
  int weak_sigma = -1, weak_x = -1;       // weak_y, weak_z follow weak_x
  int flag_sigma = -1;                    // map_weak_sigma_m, for a run without `degenerate`
  int map_sigma = -1, map_rotation = -1;  // map_weak_sigma_m, map_rotation_sigma_deg
};

int required(const NumericCsv& table, const std::string& name, const std::string& source) {
  const int index = table.column(name);
  if (index < 0) throw IoError(source + ": expected a column " + name + " in the header");
  return index;
}

// covariance_00 .. covariance_55 in a row, or -1 when the run has none.
int covariance_columns(const NumericCsv& table, const std::string& source) {
  const int first = table.column("covariance_00");
  if (first < 0) return -1;
  for (int k = 0; k < 36; ++k) {
    const std::string name = "covariance_" + std::to_string(k / 6) + std::to_string(k % 6);
    if (table.column(name) != first + k)
      throw IoError(source + ": expected the column " + name + " after covariance_00's");
  }
  return first;
}

// The weakest direction's columns `prefix`_sigma_m, `prefix`_x, _y, _z.
bool weakest_columns(const NumericCsv& table, const std::string& prefix, Columns& columns) {
  columns.weak_sigma = table.column(prefix + "_sigma_m");
  columns.weak_x = table.column(prefix + "_x");
  return columns.weak_sigma >= 0 && columns.weak_x >= 0 &&
         table.column(prefix + "_y") == columns.weak_x + 1 &&
         table.column(prefix + "_z") == columns.weak_x + 2;
}

Columns find_columns(const NumericCsv& table, const std::string& source, RunDegeneration& run) {
  Columns columns;
  columns.frame = required(table, "frame", source);
  columns.degenerate = table.column("degenerate");
  columns.matched = table.column("matched");
  columns.map_sigma = table.column("map_weak_sigma_m");
  columns.map_rotation = table.column("map_rotation_sigma_deg");
  run.flag_source = columns.degenerate >= 0 ? FlagSource::kPublished : FlagSource::kCorrespondences;
  if (columns.degenerate < 0) columns.flag_sigma = required(table, "map_weak_sigma_m", source);
  columns.covariance = covariance_columns(table, source);
  if (columns.covariance >= 0) {
    run.uncertainty_source = UncertaintySource::kCovariance;
  } else if (weakest_columns(table, "estimate_weak", columns)) {
    run.uncertainty_source = UncertaintySource::kEstimateWeakest;
  } else if (weakest_columns(table, "map_weak", columns)) {
    run.uncertainty_source = UncertaintySource::kCorrespondenceWeakest;
  } else {
    throw IoError(source +
                  ": expected the columns covariance_00..covariance_55, estimate_weak_* or "
                  "map_weak_* (sigma_m, x, y, z)");
  }
  return columns;
}

bool flag(double value, const std::string& place, const char* name) {
  if (value != 0.0 && value != 1.0)
    throw IoError(place + ": expected " + name + " 0 or 1, found " + std::to_string(value));
  return value == 1.0;
}

void read_uncertainty(const std::vector<double>& row, const Columns& columns,
                      const std::string& place, RunScan& scan) {
  if (columns.covariance >= 0) {
    Eigen::Matrix3d block;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        block(r, c) = row[columns.covariance + (r + 3) * 6 + (c + 3)];
    if (!block.allFinite()) throw IoError(place + ": expected a finite covariance");
    scan.translation_covariance = block;
    return;
  }
  scan.weak_sigma_m = row[columns.weak_sigma];
  scan.weak_direction << row[columns.weak_x], row[columns.weak_x + 1], row[columns.weak_x + 2];
  if (std::isnan(scan.weak_sigma_m) || !scan.weak_direction.allFinite() ||
      std::fabs(scan.weak_direction.norm() - 1.0) > 1e-3) {
    throw IoError(place + ": expected a sigma and a unit weakest direction");
  }
}

RunDegeneration converted(const NumericCsv& table, const std::string& source,
                          double degenerate_sigma_m) {
  RunDegeneration run;
  const Columns columns = find_columns(table, source, run);
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const std::vector<double>& row = table.rows[i];
    const std::string place = source + ":" + std::to_string(table.lines[i]);
    RunScan& scan = run.scans.emplace_back();
    const double frame = row[columns.frame];
    if (!(frame >= 0.0) || frame != std::floor(frame) || frame > 1e9)
      throw IoError(place + ": expected the frame, a non-negative integer");
    scan.frame = static_cast<int>(frame);
    // A run without the flag: map_optimization's test (pipeline.cpp) on the correspondences'.
    scan.degenerate = columns.degenerate >= 0 ? flag(row[columns.degenerate], place, "degenerate")
                                              : !(row[columns.flag_sigma] <= degenerate_sigma_m);
    if (columns.matched >= 0) {
      scan.matched = flag(row[columns.matched], place, "matched");
    } else if (columns.map_sigma >= 0 && columns.map_rotation >= 0) {
      // An unmatched scan's correspondences' information is zero (MapMatchResult): nothing fixed.
      scan.matched = !(std::isinf(row[columns.map_sigma]) && std::isinf(row[columns.map_rotation]));
    }
    read_uncertainty(row, columns, place, scan);
  }
  return run;
}

}  // namespace

const char* to_string(FlagSource source) {
  return source == FlagSource::kPublished ? "published" : "correspondences";
}

const char* to_string(UncertaintySource source) {
  switch (source) {
    case UncertaintySource::kCovariance:
      return "covariance";
    case UncertaintySource::kEstimateWeakest:
      return "estimate_weakest";
    case UncertaintySource::kCorrespondenceWeakest:
      return "correspondence_weakest";
  }
  return "?";
}

RunDegeneration read_degeneration_csv(const std::string& path, double degenerate_sigma_m) {
  return converted(read_csv_with_header(path), path, degenerate_sigma_m);
}

RunDegeneration parse_degeneration_csv(const std::string& text, const std::string& source,
                                       double degenerate_sigma_m) {
  return converted(parse_csv_with_header(text, source), source, degenerate_sigma_m);
}

}  // namespace adaptive_lego_loam
