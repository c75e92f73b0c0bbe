#include "adaptive_lego_loam/core/loop_closure/place_descriptor.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/fast_atan2.h"

namespace adaptive_lego_loam {
namespace {

constexpr float kHeightStep = 0.1f;  // m per unit of a cell
constexpr float kMaxHeight = 25.5f;  // m above -height_offset: 255 units

}  // namespace

PlaceDescriptor::PlaceDescriptor(const PlaceRecognitionParams& params)
    : rings_(params.rings),
      sectors_(params.sectors),
      max_radius_(static_cast<float>(params.max_radius)),
      height_offset_(static_cast<float>(params.height_offset)),
      cells_(static_cast<std::size_t>(params.rings) * params.sectors, 0) {}

void PlaceDescriptor::add(const Cloud& points, const Eigen::Matrix3f& level) {
  const float ring_per_m = rings_ / max_radius_;
  const float sector_per_rad = sectors_ / (2.f * float(M_PI));
  for (const CloudPoint& p : points) {
    const Eigen::Vector3f q = level * p.getVector3fMap();
    const float radius = std::sqrt(q.x() * q.x() + q.y() * q.y());
    if (!(radius < max_radius_) || !std::isfinite(q.z())) continue;
    const int ring = std::min(rings_ - 1, static_cast<int>(radius * ring_per_m));
    const int sector = std::min(
        sectors_ - 1, static_cast<int>((fast_atan2(q.y(), q.x()) + float(M_PI)) * sector_per_rad));
    const float height = std::clamp(q.z() + height_offset_, kHeightStep, kMaxHeight);
    uint8_t& cell = cells_[static_cast<std::size_t>(sector) * rings_ + ring];
    cell = std::max<uint8_t>(cell, static_cast<uint8_t>(height / kHeightStep + 0.5f));
  }
}

void PlaceDescriptor::finish() {
  ring_key_.assign(rings_, 0.f);
  sector_key_.assign(sectors_, 0.f);
  column_norm_.assign(sectors_, 0.f);
  occupied_ = 0;
  for (int sector = 0; sector < sectors_; ++sector) {
    const uint8_t* column = &cells_[static_cast<std::size_t>(sector) * rings_];
    float squared = 0.f;
    for (int ring = 0; ring < rings_; ++ring) {
      const float height = column[ring] * kHeightStep;
      ring_key_[ring] += height / sectors_;
      sector_key_[sector] += height / rings_;
      squared += float(column[ring]) * column[ring];
      occupied_ += column[ring] > 0;
    }
    column_norm_[sector] = std::sqrt(squared);
  }
}

double PlaceDescriptor::distance_at(const PlaceDescriptor& other, int shift) const {
  double similarity = 0.0;
  int columns = 0;
  for (int sector = 0; sector < sectors_; ++sector) {
    const int other_sector = (sector + shift) % sectors_;
    const float norm = column_norm_[sector], other_norm = other.column_norm_[other_sector];
    if (norm == 0.f || other_norm == 0.f) continue;
    const uint8_t* a = &cells_[static_cast<std::size_t>(sector) * rings_];
    const uint8_t* b = &other.cells_[static_cast<std::size_t>(other_sector) * rings_];
    int dot = 0;
    for (int ring = 0; ring < rings_; ++ring)
      dot += int(a[ring]) * b[ring];
    similarity += dot / (double(norm) * other_norm);
    ++columns;
  }
  return columns == 0 ? 1.0 : 1.0 - similarity / columns;
}

double PlaceDescriptor::distance(const PlaceDescriptor& other, int* best_shift) const {
  if (other.rings_ != rings_ || other.sectors_ != sectors_ || empty() || other.empty()) {
    if (best_shift) *best_shift = 0;
    return 1.0;
  }
  // The sector keys' L1 distance at every shift; the best few, and their neighbours, in full.
  constexpr int kCoarseShifts = 3;
  std::vector<std::pair<float, int>> coarse(sectors_);
  for (int shift = 0; shift < sectors_; ++shift) {
    float sum = 0.f;
    for (int sector = 0; sector < sectors_; ++sector)
      sum += std::fabs(sector_key_[sector] - other.sector_key_[(sector + shift) % sectors_]);
    coarse[shift] = {sum, shift};
  }
  const int kept = std::min(kCoarseShifts, sectors_);
  std::partial_sort(coarse.begin(), coarse.begin() + kept, coarse.end());
  double best = 2.0;
  int shift_of_best = 0;
  for (int k = 0; k < kept; ++k) {
    for (int near = -1; near <= 1; ++near) {
      const int shift = (coarse[k].second + near + sectors_) % sectors_;
      const double d = distance_at(other, shift);
      if (d < best || (d == best && shift < shift_of_best)) {
        best = d;
        shift_of_best = shift;
      }
    }
  }
  if (best_shift) *best_shift = shift_of_best;
  return best;
}

double PlaceDescriptor::yaw_of_shift(int shift) const {
  // A point at this keyframe's azimuth a lies at other's a + yaw when this keyframe is turned by
  // yaw relative to the other: its sector s matches other's s + shift.
  const double yaw = 2.0 * M_PI * shift / sectors_;
  return std::remainder(yaw, 2.0 * M_PI);
}

}  // namespace adaptive_lego_loam
