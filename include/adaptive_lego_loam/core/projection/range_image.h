#pragma once
// docs/METHOD.md, step 1: the scan projected to a rows x columns range image.

#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

// The angular layout of the image: what the clustering stages need to know about the sensor.
struct RangeImageGeometry {
  int rows = 0;
  int cols = 0;
  std::vector<double> row_elevation_rad;  // ascending, one per row
  double col_step_rad = 0.0;

  explicit RangeImageGeometry(const SensorParams& sensor);
  RangeImageGeometry() = default;
  // Angle between the beams of two rows (the vertical step of the range image).
  double row_gap_rad(int row_a, int row_b) const;
};

struct ProjectionStats {
  int input_points = 0;
  int projected = 0;     // points that own a cell
  int non_finite = 0;    // NaN or Inf coordinates
  int out_of_range = 0;  // closer than min_range or farther than max_range
  int outside_rows = 0;  // ring out of range, or elevation beyond the outermost beams
  int displaced = 0;     // moved to a free neighbouring column (counted in projected)
  int collisions = 0;    // lost to a cell and both its column neighbours already taken
  int valid() const { return projected + collisions; }
};

class RangeImage {
 public:
  static constexpr int kNoPoint = -1;

  const RangeImageGeometry& geometry() const { return geometry_; }
  int rows() const { return geometry_.rows; }
  int cols() const { return geometry_.cols; }
  int size() const { return geometry_.rows * geometry_.cols; }
  int cell(int row, int col) const { return row * geometry_.cols + col; }
  int row_of(int cell) const { return cell / geometry_.cols; }
  int col_of(int cell) const { return cell % geometry_.cols; }
  // Column index wrapped into [0, cols).
  int wrap_col(int col) const {
    const int c = col % geometry_.cols;
    return c < 0 ? c + geometry_.cols : c;
  }

  bool occupied(int cell) const { return source_[cell] != kNoPoint; }
  float range(int cell) const { return range_[cell]; }
  const std::vector<float>& ranges() const { return range_; }  // per cell, 0 when empty
  const ScanPoint& point(int cell) const { return points_[cell]; }
  int source_index(int cell) const { return source_[cell]; }  // index in the input scan
  // flags[cell] = 1 where the cell is occupied and not flagged in `excluded` (may be empty).
  void mark_occupied(const std::vector<uint8_t>& excluded, std::vector<uint8_t>& flags) const;
  const ProjectionStats& stats() const { return stats_; }

 private:
  friend class RangeProjector;
  RangeImageGeometry geometry_;
  std::vector<float> range_;
  std::vector<ScanPoint> points_;
  std::vector<int32_t> source_;
  ProjectionStats stats_;
  // Scratch of the projection, kept to reuse its memory between scans.
  struct Candidate {
    int32_t source;
    int32_t cell;
    float fraction;  // position inside the cell's column, in [0, 1)
    float range;
  };
  std::vector<Candidate> candidates_;
  std::vector<int32_t> cell_start_;
  std::vector<int32_t> by_cell_;  // candidates in placement order
  std::vector<float> row_last_position_;
  std::vector<int32_t> row_wraps_;
};

class RangeProjector {
 public:
  explicit RangeProjector(const SensorParams& sensor);
  // Projects the scan into `image`, reusing its buffers. Bad points never throw: they are
  // skipped and counted in image.stats(). Throws std::invalid_argument only when the config asks
  // for rings the cloud does not have.
  void project(const Scan& scan, RangeImage& image) const;
  // The row a point falls in by its elevation, or -1 outside the beams (exposed for tests).
  int row_from_elevation(float x, float y, float z) const;
  const RangeImageGeometry& geometry() const { return geometry_; }
  bool uses_ring(const Scan& scan) const;

 private:
  int row_of(const ScanPoint& p, bool use_ring) const;
  // Returns whether every row arrived in azimuth order.
  bool collect_candidates(const Scan& scan, RangeImage& image) const;
  void sort_candidates_by_cell(RangeImage& image) const;
  void place_candidates(const Scan& scan, RangeImage& image) const;

  SensorParams sensor_;
  RangeImageGeometry geometry_;
  std::vector<float> tan_elevation_;  // per row
  std::vector<float> offset_m_;       // per row
  float row_tolerance_tan_low_ = 0.f;
  float row_tolerance_tan_high_ = 0.f;
  // First guess of the row from the slope seen from the mean beam origin.
  void build_row_lookup();
  float mean_offset_m_ = 0.f;
  float lookup_min_slope_ = 0.f;
  float lookup_bins_per_slope_ = 1.f;
  std::vector<int16_t> row_lookup_;
};

// Empty when the projection kept at least one point; else one line saying why none was kept,
// for the log of a node or tool that drops the scan.
std::string projection_problem(const ProjectionStats& stats);

}  // namespace adaptive_lego_loam
