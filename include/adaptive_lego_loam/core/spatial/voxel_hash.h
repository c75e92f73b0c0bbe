#pragma once
// Voxel keys and the open-addressing table the voxel filter and the voxel map keep per voxel: one
// probe per lookup, no allocation per voxel (std::unordered_map's nodes cost more than the work).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace adaptive_lego_loam {

// A voxel's integer coordinates packed in 21 bits per axis (+-200 km at 0.2 m, as PCL's index).
inline uint64_t pack_voxel_key(int64_t x, int64_t y, int64_t z) {
  auto bits = [](int64_t index) { return static_cast<uint64_t>(index + (1 << 20)) & 0x1FFFFF; };
  return bits(x) | bits(y) << 21 | bits(z) << 42;
}

// floor() by truncation: exactly std::floor for finite coordinates, inline where std::floor is a
// library call unless the build targets SSE4.1.
inline int64_t voxel_index(float coordinate, double inverse_leaf) {
  const double scaled = coordinate * inverse_leaf;
  const auto truncated = static_cast<int64_t>(scaled);
  return truncated - (scaled < static_cast<double>(truncated) ? 1 : 0);
}

// The key of the voxel holding point `p` (anything with x, y, z).
template <class Point>
uint64_t voxel_key(const Point& p, double inverse_leaf) {
  return pack_voxel_key(voxel_index(p.x, inverse_leaf), voxel_index(p.y, inverse_leaf),
                        voxel_index(p.z, inverse_leaf));
}

// Maps voxel keys to values. Linear probing over a power-of-two array at most half full;
// references stay valid until the next insertion or erasure.
template <class Value>
class VoxelHashTable {
 public:
  Value* find(uint64_t key) {
    if (slots_.empty()) return nullptr;
    for (std::size_t i = home(key);; i = (i + 1) & (slots_.size() - 1)) {
      if (slots_[i].key == key) return &slots_[i].value;
      if (slots_[i].key == kEmpty) return nullptr;
    }
  }
  const Value* find(uint64_t key) const { return const_cast<VoxelHashTable*>(this)->find(key); }

  // The key's value, value-initialised when the key is new; `inserted` tells which.
  Value& find_or_insert(uint64_t key, bool* inserted = nullptr) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = home(key);
    while (slots_[i].key != key && slots_[i].key != kEmpty)
      i = (i + 1) & mask;
    const bool is_new = slots_[i].key == kEmpty;
    if (is_new) {
      slots_[i].key = key;
      ++used_;
    }
    if (inserted) *inserted = is_new;
    return slots_[i].value;
  }

  // Linear probing's backward-shift deletion: later entries of the probe run move up, so that no
  // lookup stops early at the hole.
  void erase(uint64_t key) {
    if (slots_.empty()) return;
    const std::size_t mask = slots_.size() - 1;
    std::size_t hole = home(key);
    while (slots_[hole].key != key) {
      if (slots_[hole].key == kEmpty) return;
      hole = (hole + 1) & mask;
    }
    slots_[hole] = Slot();
    --used_;
    for (std::size_t next = (hole + 1) & mask; slots_[next].key != kEmpty;
         next = (next + 1) & mask) {
      const std::size_t wanted = home(slots_[next].key);
      // The entry may fill the hole when its home is not cyclically in (hole, next].
      const bool stays =
          hole < next ? (wanted > hole && wanted <= next) : (wanted > hole || wanted <= next);
      if (stays) continue;
      slots_[hole] = std::move(slots_[next]);
      slots_[next] = Slot();
      hole = next;
    }
  }

  // Starts loading the key's home slot into the cache (for a lookup soon after).
  void prefetch(uint64_t key) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(key)]);
  }

  // Empties the table, keeping its size (a table used again soon need not grow again).
  void clear() {
    std::fill(slots_.begin(), slots_.end(), Slot());
    used_ = 0;
  }

  // Room for `count` entries without growing (growing re-inserts every entry at once).
  void reserve(std::size_t count) {
    std::size_t slot_count = 1024;
    while (slot_count < 2 * count)
      slot_count *= 2;
    if (slot_count > slots_.size()) resize(slot_count);
  }
  std::size_t size() const { return used_; }

  // Calls visit(key, value) for every entry, in table order.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (const Slot& slot : slots_) {
      if (slot.key != kEmpty) visit(slot.key, slot.value);
    }
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  struct Slot {
    uint64_t key = kEmpty;
    Value value{};
  };

  std::size_t home(uint64_t key) const {
    // Fibonacci hashing: the top bits of key * 2^64 / phi.
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }

  void grow() { resize(std::max<std::size_t>(1024, 2 * slots_.size())); }

  void resize(std::size_t slot_count) {
    std::vector<Slot> old(slot_count);
    old.swap(slots_);
    used_ = 0;
    shift_ = 64;
    for (std::size_t size = slots_.size(); size > 1; size /= 2)
      --shift_;
    for (Slot& slot : old) {
      if (slot.key != kEmpty) find_or_insert(slot.key) = std::move(slot.value);
    }
  }

  std::vector<Slot> slots_;
  std::size_t used_ = 0;
  int shift_ = 64;
};

}  // namespace adaptive_lego_loam
