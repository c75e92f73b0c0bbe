#pragma once
// A spinning LiDAR measured from a few of its scans (derive_config, docs/SENSORS.md): its rows
// (from the ring field, from the order of the points when the file holds one laser after the
// other, as KITTI's do, else from clustering the elevations), each beam's elevation and the height
// of its origin, the firings per turn from the azimuth spacing, the ranges, the ground plane,
// the points' times and whether the sweep looks de-skewed. A cloud that is not from a spinning
// LiDAR (a solid-state field of view, a rosette pattern, several sensors merged) says so.

#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

struct SurveyedBeam {
  double elevation_deg = 0.0;
  double offset_m = 0.0;    // height of the beam's origin above the sensor origin
  double spread_deg = 0.0;  // RMS of its points' elevations about the fitted beam
  long points = 0;
  int ring = -1;  // the driver's ring (or the laser's place in the file); -1 when clustered
};

struct SensorSurvey {
  int scans = 0;
  std::string not_spinning;  // why the clouds are not a spinning LiDAR's; empty when they are
  std::string rows_from;     // "the ring field", "the order of the points", "the elevations"
  bool ring_field = false;
  std::vector<SurveyedBeam> beams;  // bottom-up
  std::vector<int> ring_to_row;     // empty when the rings count the rows from the bottom
  bool offsets_matter = false;      // the origins move a point by a tenth of a row spacing
  double typical_range_m = 0.0;     // median horizontal range of the points
  int firings = 0;                  // per turn, from the azimuth step
  int columns = 0;                  // the firings, or room for the fullest row's points
  double azimuth_step_deg = 0.0;
  double min_range_m = 0.0, max_range_m = 0.0;
  double azimuth_coverage = 0.0;  // share of the 1-deg azimuth bins that hold points
  bool has_time = false;
  double time_span_s = 0.0;   // of a sweep's point times (median over the scans)
  double stamp_step_s = 0.0;  // median step between the scans' stamps (0: one scan)
  double scan_period_s = 0.1;
  std::string period_from;
  std::optional<bool> deskewed;  // nothing: cannot tell (the sensor stood still)
  // The share of neighbouring points whose ranges jump: across the seam (first and last columns,
  // a sweep apart in time) and elsewhere; a raw sweep of a moving sensor jumps at its seam.
  double seam_jump_share = 0.0, neighbour_jump_share = 0.0;
  long seam_pairs = 0;
  double scan_to_scan_change_m = 0.0;
  std::optional<double> sensor_height_m, ground_tilt_deg;
  int ground_rows = 0;
  std::vector<std::string> report;  // a line per finding
};

// Throws std::invalid_argument when `scans` holds no point.
SensorSurvey survey_sensor(const std::vector<Scan>& scans);

// The sensor section the survey measured: rows, beams (evenly spaced ones as their limits),
// beam origins where they matter, ring_to_row, columns, ranges, ground rows, scan period,
// deskewed.
SensorParams surveyed_sensor(const SensorSurvey& survey, const std::string& name);

}  // namespace adaptive_lego_loam
