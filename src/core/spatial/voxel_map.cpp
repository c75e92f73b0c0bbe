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
    if (i + kAhead < points.size()) voxels_.prefetch(keys[i + kAhead]);
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
  voxels_.clear();
  cell_refs_.clear();
  cells_.clear();
  free_cells_.clear();
}

void VoxelMap::reserve(std::size_t voxels) {
  voxels_.reserve(voxels);
  cell_refs_.reserve(voxels / 8);
}

void VoxelMap::add_point(const CloudPoint& p, uint64_t key) {
  bool inserted = false;
  Voxel& voxel = voxels_.find_or_insert(key, &inserted);
  if (inserted) attach(key, voxel);
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
  Voxel* voxel = voxels_.find(key);
  if (!voxel) return;
  voxel->sum[0] -= p.x;
  voxel->sum[1] -= p.y;
  voxel->sum[2] -= p.z;
  voxel->sum[3] -= p.intensity;
  if (--voxel->count == 0) {
    detach(*voxel);
    voxels_.erase(key);
    return;
  }
  cells_[voxel->cell].centroids[voxel->slot] =
      Eigen::Vector3f(static_cast<float>(voxel->sum[0] / voxel->count),
                      static_cast<float>(voxel->sum[1] / voxel->count),
                      static_cast<float>(voxel->sum[2] / voxel->count));
}

// Gives a new voxel a slot in its cell (and the cell a place in cells_ when it is new).
void VoxelMap::attach(uint64_t key, Voxel& voxel) {
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
  voxel.cell = ref.index_plus_one - 1;
  Cell& cell = cells_[voxel.cell];
  voxel.slot = static_cast<uint32_t>(cell.centroids.size());
  cell.centroids.emplace_back(0.f, 0.f, 0.f);
  cell.voxel_keys.push_back(key);
  ref.count = static_cast<uint32_t>(cell.centroids.size());
  ref.centroids = cell.centroids.data();
}

// Frees an emptied voxel's slot: the cell's last voxel takes it.
void VoxelMap::detach(const Voxel& voxel) {
  Cell& cell = cells_[voxel.cell];
  const uint64_t moved_key = cell.voxel_keys.back();
  cell.centroids[voxel.slot] = cell.centroids.back();
  cell.voxel_keys[voxel.slot] = moved_key;
  voxels_.find(moved_key)->slot = voxel.slot;
  cell.centroids.pop_back();
  cell.voxel_keys.pop_back();
  if (cell.centroids.empty()) {
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
      const Voxel& voxel = *voxels_.find(cell.voxel_keys[slot]);
      CloudPoint p;
      p.getVector3fMap() = cell.centroids[slot];
      p.intensity = static_cast<float>(voxel.sum[3] / voxel.count);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace adaptive_lego_loam
