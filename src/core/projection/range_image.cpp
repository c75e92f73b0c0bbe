#include "adaptive_lego_loam/core/projection/range_image.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "adaptive_lego_loam/core/common/fast_atan2.h"

namespace adaptive_lego_loam {

std::string projection_problem(const ProjectionStats& stats) {
  if (stats.projected > 0) return "";
  if (stats.input_points == 0) return "empty scan: no point";
  return "no valid point among " + std::to_string(stats.input_points) + ": " +
         std::to_string(stats.non_finite) + " NaN/Inf, " + std::to_string(stats.out_of_range) +
         " out of range, " + std::to_string(stats.outside_rows) + " outside the beams";
}

RangeImageGeometry::RangeImageGeometry(const SensorParams& sensor)
    : rows(sensor.rows), cols(sensor.columns), col_step_rad(2.0 * M_PI / sensor.columns) {
  for (double deg : sensor.beam_angles_deg)
    row_elevation_rad.push_back(deg * M_PI / 180.0);
}

double RangeImageGeometry::row_gap_rad(int row_a, int row_b) const {
  return std::fabs(row_elevation_rad[row_a] - row_elevation_rad[row_b]);
}

void RangeImage::mark_occupied(const std::vector<uint8_t>& excluded,
                               std::vector<uint8_t>& flags) const {
  // Raw pointers: the compiler vectorises the loops only when the byte stores cannot alias the
  // vectors' own pointers.
  const int cells = size();
  flags.resize(cells);
  uint8_t* flag = flags.data();
  const int32_t* source = source_.data();
  for (int cell = 0; cell < cells; ++cell)
    flag[cell] = source[cell] != kNoPoint;
  if (excluded.empty()) return;
  const uint8_t* excluded_cell = excluded.data();
  for (int cell = 0; cell < cells; ++cell)
    flag[cell] &= !excluded_cell[cell];
}

RangeProjector::RangeProjector(const SensorParams& sensor) : sensor_(sensor), geometry_(sensor) {
  validate(sensor_, "sensor params");
  for (int row = 0; row < geometry_.rows; ++row) {
    tan_elevation_.push_back(std::tan(geometry_.row_elevation_rad[row]));
    offset_m_.push_back(sensor_.beam_offsets_m.empty() ? 0.0 : sensor_.beam_offsets_m[row]);
  }
  // Points up to one row spacing beyond the outermost beams still belong to them.
  const int last = geometry_.rows - 1;
  const double low_gap = geometry_.rows > 1 ? tan_elevation_[1] - tan_elevation_[0] : 0.01;
  const double high_gap =
      geometry_.rows > 1 ? tan_elevation_[last] - tan_elevation_[last - 1] : 0.01;
  row_tolerance_tan_low_ = low_gap;
  row_tolerance_tan_high_ = high_gap;
  build_row_lookup();
}

void RangeProjector::build_row_lookup() {
  double offset_sum = 0.0;
  for (float offset : offset_m_)
    offset_sum += offset;
  mean_offset_m_ = static_cast<float>(offset_sum / geometry_.rows);
  constexpr int kBins = 4096;
  lookup_min_slope_ = tan_elevation_.front() - row_tolerance_tan_low_;
  const float max_slope = tan_elevation_.back() + row_tolerance_tan_high_;
  lookup_bins_per_slope_ = kBins / (max_slope - lookup_min_slope_);
  row_lookup_.resize(kBins);
  int row = 0;
  for (int bin = 0; bin < kBins; ++bin) {
    const float slope = lookup_min_slope_ + (bin + 0.5f) / lookup_bins_per_slope_;
    while (row + 1 < geometry_.rows &&
           tan_elevation_[row + 1] - slope < slope - tan_elevation_[row]) {
      ++row;
    }
    row_lookup_[bin] = static_cast<int16_t>(row);
  }
}

bool RangeProjector::uses_ring(const Scan& scan) const {
  switch (sensor_.row_source) {
    case RowSource::kRing:
      if (!scan.has_ring) {
        throw std::invalid_argument(
            "sensor.row_source is 'ring' but the cloud has no ring field; use 'auto' or "
            "'elevation'");
      }
      return true;
    case RowSource::kElevation:
      return false;
    case RowSource::kAuto:
      return scan.has_ring;
  }
  return false;
}

int RangeProjector::row_from_elevation(float x, float y, float z) const {
  const float horizontal_sq = x * x + y * y;
  if (horizontal_sq <= 0.f) return -1;
  const float inverse_horizontal = 1.f / std::sqrt(horizontal_sq);
  // mismatch(row) = (z - h_row) / horizontal - tan(elevation_row) falls as the row rises when
  // the beam offsets h do not fall faster than the beams rise (true of every sensor we know at
  // its minimum range). A table on the slope seen from the mean beam origin gives a first row;
  // a short walk finds the sign change and the nearer side of it wins.
  auto mismatch = [&](int row) {
    return (z - offset_m_[row]) * inverse_horizontal - tan_elevation_[row];
  };
  const float slope = (z - mean_offset_m_) * inverse_horizontal;
  const int bin = std::clamp(static_cast<int>((slope - lookup_min_slope_) * lookup_bins_per_slope_),
                             0, static_cast<int>(row_lookup_.size()) - 1);
  int row = row_lookup_[bin];
  const int top = geometry_.rows - 1;
  float at_row = mismatch(row);
  if (at_row > 0.f) {
    // Walk up to the last row still below the point.
    while (row < top) {
      const float above = mismatch(row + 1);
      if (above <= 0.f) return at_row <= -above ? row : row + 1;
      ++row;
      at_row = above;
    }
    return at_row <= row_tolerance_tan_high_ ? top : -1;
  }
  // Walk down to the last row still above the point.
  while (row > 0) {
    const float below = mismatch(row - 1);
    if (below > 0.f) return -at_row < below ? row : row - 1;
    --row;
    at_row = below;
  }
  return -at_row <= row_tolerance_tan_low_ ? 0 : -1;
}

int RangeProjector::row_of(const ScanPoint& p, bool use_ring) const {
  if (!use_ring) return row_from_elevation(p.x, p.y, p.z);
  if (p.ring < 0) return -1;
  if (!sensor_.ring_to_row.empty()) {
    return p.ring < static_cast<int>(sensor_.ring_to_row.size()) ? sensor_.ring_to_row[p.ring] : -1;
  }
  return p.ring < geometry_.rows ? p.ring : -1;
}

void RangeProjector::project(const Scan& scan, RangeImage& image) const {
  image.geometry_ = geometry_;
  const int cells = geometry_.rows * geometry_.cols;
  image.range_.assign(cells, 0.f);
  image.points_.resize(cells);
  image.source_.assign(cells, RangeImage::kNoPoint);
  image.stats_ = ProjectionStats();
  image.stats_.input_points = static_cast<int>(scan.points.size());
  const bool azimuth_ordered = collect_candidates(scan, image);
  if (azimuth_ordered) {
    image.by_cell_.resize(image.candidates_.size());
    std::iota(image.by_cell_.begin(), image.by_cell_.end(), 0);
  } else {
    sort_candidates_by_cell(image);
  }
  place_candidates(scan, image);
}

bool RangeProjector::collect_candidates(const Scan& scan, RangeImage& image) const {
  ProjectionStats& stats = image.stats_;
  const bool use_ring = uses_ring(scan);
  const float min_range = static_cast<float>(sensor_.min_range);
  const float max_range = static_cast<float>(sensor_.max_range);
  const float cols_per_rad = static_cast<float>(geometry_.cols / (2.0 * M_PI));
  const int cols = geometry_.cols;
  image.candidates_.resize(scan.points.size());
  RangeImage::Candidate* candidate = image.candidates_.data();
  float* last_position = nullptr;
  // Whether each row arrives in azimuth order (one wrap allowed, and steps back of under a
  // column, which rows from elevation produce where beams overlap): drivers deliver points in
  // firing order, and then placing them as they come equals placing them sorted.
  image.row_last_position_.assign(geometry_.rows, -1.f);
  last_position = image.row_last_position_.data();
  auto& wraps = image.row_wraps_;
  wraps.assign(geometry_.rows, 0);
  bool ordered = true;
  for (int index = 0; index < stats.input_points; ++index) {
    const ScanPoint& p = scan.points[index];
    if (!std::isfinite(p.x + p.y + p.z)) {  // any NaN or Inf makes the sum non-finite
      ++stats.non_finite;
      continue;
    }
    const float range = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if (range < min_range || range > max_range) {
      ++stats.out_of_range;
      continue;
    }
    const int row = row_of(p, use_ring);
    if (row < 0) {
      ++stats.outside_rows;
      continue;
    }
    // Column 0 looks along -x; columns grow counter-clockwise seen from above.
    const float position = (fast_atan2(p.y, p.x) + float(M_PI)) * cols_per_rad;
    const int col = std::min(static_cast<int>(position), cols - 1);
    *candidate++ = {index, row * cols + col, position - col, range};
    if (position < last_position[row] - 1.f) {
      if (position < last_position[row] - 0.5f * cols) {
        ordered &= ++wraps[row] <= 1;
      } else {
        ordered = false;
      }
    }
    last_position[row] = position;
  }
  image.candidates_.resize(candidate - image.candidates_.data());
  return ordered;
}

// Counting sort by cell, then by position inside the cell: the placement below then walks each
// row in azimuth order whatever order the driver delivered the points in.
void RangeProjector::sort_candidates_by_cell(RangeImage& image) const {
  const auto& candidates = image.candidates_;
  auto& start = image.cell_start_;
  start.assign(image.size() + 1, 0);
  for (const auto& candidate : candidates)
    ++start[candidate.cell + 1];
  for (std::size_t cell = 1; cell < start.size(); ++cell)
    start[cell] += start[cell - 1];
  image.by_cell_.resize(candidates.size());
  std::vector<int32_t>& cursor = image.source_;  // free until placement: borrow it
  std::copy(start.begin(), start.end() - 1, cursor.begin());
  for (int32_t i = 0; i < static_cast<int32_t>(candidates.size()); ++i) {
    image.by_cell_[cursor[candidates[i].cell]++] = i;
  }
  std::fill(cursor.begin(), cursor.end(), RangeImage::kNoPoint);
  for (int cell = 0; cell < image.size(); ++cell) {
    // Cells hold one to three candidates: an insertion sort (stable) is all it takes.
    for (int32_t k = start[cell] + 1; k < start[cell + 1]; ++k) {
      const int32_t moving = image.by_cell_[k];
      int32_t j = k;
      for (; j > start[cell] &&
             candidates[image.by_cell_[j - 1]].fraction > candidates[moving].fraction;
           --j) {
        image.by_cell_[j] = image.by_cell_[j - 1];
      }
      image.by_cell_[j] = moving;
    }
  }
}

void RangeProjector::place_candidates(const Scan& scan, RangeImage& image) const {
  ProjectionStats& stats = image.stats_;
  const int cols = geometry_.cols;
  for (const int32_t i : image.by_cell_) {
    const RangeImage::Candidate& candidate = image.candidates_[i];
    int cell = candidate.cell;
    if (image.source_[cell] != RangeImage::kNoPoint) {
      // The cell is taken (KITTI's scans and dual-return drivers put some points closer than one
      // column apart): use the free neighbour on the side the point leans to, else the other.
      const int row_start = cell - cell % cols;
      const int col = cell - row_start;
      const int right = row_start + (col + 1) % cols;
      const int left = row_start + (col + cols - 1) % cols;
      const bool leans_right = candidate.fraction >= 0.5f;
      const int first = leans_right ? right : left;
      const int second = leans_right ? left : right;
      if (image.source_[first] == RangeImage::kNoPoint) {
        cell = first;
      } else if (image.source_[second] == RangeImage::kNoPoint) {
        cell = second;
      } else {
        ++stats.collisions;
        continue;
      }
      ++stats.displaced;
    }
    image.range_[cell] = candidate.range;
    image.points_[cell] = scan.points[candidate.source];
    image.source_[cell] = candidate.source;
    ++stats.projected;
  }
}

}  // namespace adaptive_lego_loam
