#include "adaptive_lego_loam/core/spatial/voxel_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "adaptive_lego_loam/core/spatial/nearest_candidates.h"

namespace adaptive_lego_loam {
namespace {

int64_t floor_divide(int64_t value, int64_t divisor) {
  const int64_t quotient = value / divisor;
  return quotient * divisor > value ? quotient - 1 : quotient;
}

}  // namespace

VoxelMap::VoxelMap(double leaf, double max_radius)
    : inverse_leaf_(1.0 / leaf),
      voxels_per_cell_(std::max<int64_t>(1, static_cast<int64_t>(std::ceil(max_radius / leaf)))),
      cell_size_(voxels_per_cell_ * leaf),
      cell_size_f_(static_cast<float>(cell_size_)),
      max_squared_radius_(static_cast<float>(max_radius * max_radius)) {}

int64_t VoxelMap::cell_of(int64_t voxel_index) const {
  return floor_divide(voxel_index, voxels_per_cell_);
}

template <class Visit>
void VoxelMap::for_each_key(const Cloud& points, Visit&& visit) {
  // The table is far larger than the caches: a slot asked for a few points ahead is there in time.
  constexpr std::size_t kAhead = 8;
  std::vector<uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    keys[i] = voxel_key(points[i], inverse_leaf_);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i + kAhead < points.size()) voxel_index_.prefetch(keys[i + kAhead]);
    visit(points[i], keys[i]);
  }
}

void VoxelMap::add(const Cloud& points) {
  for_each_key(points, [this](const CloudPoint& p, uint64_t key) { add_point(p, key); });
}

void VoxelMap::remove(const Cloud& points) {
  for_each_key(points, [this](const CloudPoint& p, uint64_t key) { remove_point(p, key); });
}

void VoxelMap::clear() {
  voxel_index_.clear();
  voxels_.clear();
  free_voxels_.clear();
  cell_refs_.clear();
  cells_.clear();
  free_cells_.clear();
}

void VoxelMap::reserve(std::size_t voxels) {
  voxel_index_.reserve(voxels);
  voxels_.reserve(voxels);
  cell_refs_.reserve(voxels / 8);
}

void VoxelMap::add_point(const CloudPoint& p, uint64_t key) {
  bool inserted = false;
  uint32_t& index = voxel_index_.find_or_insert(key, &inserted);
  if (inserted) index = attach(key);
  Voxel& voxel = voxels_[index];
  voxel.sum[0] += p.x;
  voxel.sum[1] += p.y;
  voxel.sum[2] += p.z;
  voxel.sum[3] += p.intensity;
  ++voxel.count;
  cells_[voxel.cell].centroids[voxel.slot] =
      Eigen::Vector3f(static_cast<float>(voxel.sum[0] / voxel.count),
                      static_cast<float>(voxel.sum[1] / voxel.count),
                      static_cast<float>(voxel.sum[2] / voxel.count));
}

void VoxelMap::remove_point(const CloudPoint& p, uint64_t key) {
  const uint32_t* index = voxel_index_.find(key);
  if (!index) return;
  Voxel& voxel = voxels_[*index];
  voxel.sum[0] -= p.x;
  voxel.sum[1] -= p.y;
  voxel.sum[2] -= p.z;
  voxel.sum[3] -= p.intensity;
  if (--voxel.count == 0) {
    detach(*index);
    voxel_index_.erase(key);
    return;
  }
  cells_[voxel.cell].centroids[voxel.slot] =
      Eigen::Vector3f(static_cast<float>(voxel.sum[0] / voxel.count),
                      static_cast<float>(voxel.sum[1] / voxel.count),
                      static_cast<float>(voxel.sum[2] / voxel.count));
}

// A new voxel: an entry in voxels_ and a slot in its cell (and the cell a place in cells_ when it
// is new). Returns its index in voxels_.
uint32_t VoxelMap::attach(uint64_t key) {
  auto unpack = [](uint64_t packed, int shift) {
    return static_cast<int64_t>((packed >> shift) & 0x1FFFFF) - (1 << 20);
  };
  const uint64_t cell_key =
      pack_voxel_key(cell_of(unpack(key, 0)), cell_of(unpack(key, 21)), cell_of(unpack(key, 42)));
  CellRef& ref = cell_refs_.find_or_insert(cell_key);
  if (ref.index_plus_one == 0) {
    if (free_cells_.empty()) {
      cells_.emplace_back();
      ref.index_plus_one = static_cast<uint32_t>(cells_.size());
    } else {
      ref.index_plus_one = free_cells_.back() + 1;
      free_cells_.pop_back();
    }
    cells_[ref.index_plus_one - 1].key = cell_key;
  }
  uint32_t index;
  if (free_voxels_.empty()) {
    index = static_cast<uint32_t>(voxels_.size());
    voxels_.emplace_back();
  } else {
    index = free_voxels_.back();
    free_voxels_.pop_back();
    voxels_[index] = Voxel();
  }
  Voxel& voxel = voxels_[index];
  voxel.cell = ref.index_plus_one - 1;
  Cell& cell = cells_[voxel.cell];
  voxel.slot = static_cast<uint32_t>(cell.centroids.size());
  cell.centroids.emplace_back(0.f, 0.f, 0.f);
  cell.voxels.push_back(index);
  ref.count = static_cast<uint32_t>(cell.centroids.size());
  ref.centroids = cell.centroids.data();
  return index;
}

// Frees an emptied voxel's entry and its slot in its cell, which the cell's last voxel takes.
void VoxelMap::detach(uint32_t index) {
  const Voxel& voxel = voxels_[index];
  Cell& cell = cells_[voxel.cell];
  const uint32_t moved = cell.voxels.back();
  cell.centroids[voxel.slot] = cell.centroids.back();
  cell.voxels[voxel.slot] = moved;
  voxels_[moved].slot = voxel.slot;
  cell.centroids.pop_back();
  cell.voxels.pop_back();
  free_voxels_.push_back(index);
  if (cell.centroids.empty()) {
    // A freed cell's storage goes with it: kept, every reused cell would grow to the largest
    // any cell ever held.
    cell.centroids = {};
    cell.voxels = {};
    cell_refs_.erase(cell.key);
    free_cells_.push_back(voxel.cell);
  } else {
    cell_refs_.find(cell.key)->count = static_cast<uint32_t>(cell.centroids.size());
  }
}

int VoxelMap::nearest(const Eigen::Vector3f& query, int k, Eigen::Vector3f* points,
                      float* squared_distances, float max_squared_distance) const {
  if (k <= 0 || empty()) return 0;
  const float bound = std::min(max_squared_distance, max_squared_radius_);
  NearestCandidates<Eigen::Vector3f> found{
      k, 0, points, squared_distances,
      std::nextafter(bound, std::numeric_limits<float>::infinity())};
  // A cell is at least the radius wide, so the ball around the query lies in the 3 x 3 x 3 cells
  // around the query's own. Along each axis they are visited own, nearer neighbour, farther one:
  // the own cell usually holds the nearest points, and a tight bound skips most of the others.
  int64_t cells[3][3];
  float gap_squared[3][3];
  for (int a = 0; a < 3; ++a) {
    const int64_t cell = cell_of(voxel_index(query[a], inverse_leaf_));
    const float into = static_cast<float>(query[a] - cell * cell_size_);
    const float below = std::max(0.f, into), above = std::max(0.f, cell_size_f_ - into);
    const bool lower_nearer = below <= above;
    cells[a][0] = cell;
    cells[a][1] = lower_nearer ? cell - 1 : cell + 1;
    cells[a][2] = lower_nearer ? cell + 1 : cell - 1;
    gap_squared[a][0] = 0.f;
    gap_squared[a][1] = lower_nearer ? below * below : above * above;
    gap_squared[a][2] = lower_nearer ? above * above : below * below;
  }
  for (int ix = 0; ix < 3; ++ix) {
    for (int iy = 0; iy < 3; ++iy) {
      for (int iz = 0; iz < 3; ++iz) {
        const float gap = gap_squared[0][ix] + gap_squared[1][iy] + gap_squared[2][iz];
        if (gap >= found.worst) continue;
        const CellRef* ref =
            cell_refs_.find(pack_voxel_key(cells[0][ix], cells[1][iy], cells[2][iz]));
        if (!ref) continue;
        for (const Eigen::Vector3f* c = ref->centroids; c != ref->centroids + ref->count; ++c) {
          const float dx = query[0] - (*c)[0], dy = query[1] - (*c)[1], dz = query[2] - (*c)[2];
          const float distance = dx * dx + dy * dy + dz * dz;
          if (distance < found.worst) found.add(distance, *c);
        }
      }
    }
  }
  return found.count;
}

Cloud VoxelMap::centroids() const {
  Cloud out;
  out.reserve(size());
  for (const Cell& cell : cells_) {
    for (std::size_t slot = 0; slot < cell.centroids.size(); ++slot) {
      const Voxel& voxel = voxels_[cell.voxels[slot]];
      CloudPoint p;
      p.getVector3fMap() = cell.centroids[slot];
      p.intensity = static_cast<float>(voxel.sum[3] / voxel.count);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace adaptive_lego_loam
