#include "adaptive_lego_loam/core/voxel_filter.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {

uint64_t VoxelSums::key_of(const CloudPoint& p) const {
  // PCL's voxel index, 21 bits per axis (+-200 km at 0.2 m).
  auto cell = [this](float coordinate) {
    const int64_t index = static_cast<int64_t>(std::floor(coordinate * inverse_leaf_));
    return static_cast<uint64_t>(index + (1 << 20)) & 0x1FFFFF;
  };
  return cell(p.x) | cell(p.y) << 21 | cell(p.z) << 42;
}

std::size_t VoxelSums::home(uint64_t key) const {
  // Fibonacci hashing: the top bits of key * 2^64 / phi.
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
}

VoxelSums::Slot& VoxelSums::find_or_insert(uint64_t key) {
  if (2 * (used_ + 1) > slots_.size()) grow();
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = home(key);
  while (slots_[i].key != key && slots_[i].key != kEmpty)
    i = (i + 1) & mask;
  if (slots_[i].key == kEmpty) {
    slots_[i].key = key;
    ++used_;
  }
  return slots_[i];
}

// Linear probing's backward-shift deletion: later entries of the probe run move up, so that no
// lookup stops early at the hole.
void VoxelSums::erase(std::size_t hole) {
  const std::size_t mask = slots_.size() - 1;
  slots_[hole] = Slot();
  --used_;
  for (std::size_t next = (hole + 1) & mask; slots_[next].key != kEmpty; next = (next + 1) & mask) {
    const std::size_t wanted = home(slots_[next].key);
    // The entry may fill the hole when its home is not cyclically in (hole, next].
    const bool stays =
        hole < next ? (wanted > hole && wanted <= next) : (wanted > hole || wanted <= next);
    if (stays) continue;
    slots_[hole] = slots_[next];
    slots_[next] = Slot();
    hole = next;
  }
}

void VoxelSums::grow() {
  std::vector<Slot> old(std::max<std::size_t>(1024, 2 * slots_.size()));
  old.swap(slots_);
  used_ = 0;
  shift_ = 64;
  for (std::size_t size = slots_.size(); size > 1; size /= 2)
    --shift_;
  for (const Slot& slot : old) {
    if (slot.key != kEmpty) find_or_insert(slot.key) = slot;
  }
}

void VoxelSums::clear() {
  slots_.clear();
  used_ = 0;
}

void VoxelSums::accumulate(const Cloud& points, int sign) {
  for (const CloudPoint& p : points) {
    Slot& sum = find_or_insert(key_of(p));
    sum.x += sign * double(p.x);
    sum.y += sign * double(p.y);
    sum.z += sign * double(p.z);
    sum.intensity += sign * double(p.intensity);
    sum.count += sign;
    if (sum.count == 0) erase(&sum - slots_.data());
  }
}

CloudPtr VoxelSums::centroids() const {
  CloudPtr out(new Cloud);
  out->reserve(used_);
  for (const Slot& sum : slots_) {
    if (sum.key == kEmpty) continue;
    CloudPoint p;
    p.x = static_cast<float>(sum.x / sum.count);
    p.y = static_cast<float>(sum.y / sum.count);
    p.z = static_cast<float>(sum.z / sum.count);
    p.intensity = static_cast<float>(sum.intensity / sum.count);
    out->push_back(p);
  }
  return out;
}

CloudPtr voxel_filter(const Cloud& cloud, double leaf) {
  if (leaf <= 0.0 || cloud.empty()) return CloudPtr(new Cloud(cloud));
  VoxelSums sums(leaf);
  sums.add(cloud);
  return sums.centroids();
}

}  // namespace adaptive_lego_loam
