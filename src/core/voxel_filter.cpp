#include "adaptive_lego_loam/core/voxel_filter.h"

namespace adaptive_lego_loam {

void VoxelSums::accumulate(const Cloud& points, int sign) {
  for (const CloudPoint& p : points) {
    const uint64_t key =
        pack_voxel_key(voxel_index(p.x, inverse_leaf_), voxel_index(p.y, inverse_leaf_),
                       voxel_index(p.z, inverse_leaf_));
    Sum& sum = sums_.find_or_insert(key);
    sum.x += sign * double(p.x);
    sum.y += sign * double(p.y);
    sum.z += sign * double(p.z);
    sum.intensity += sign * double(p.intensity);
    sum.count += sign;
    if (sum.count == 0) sums_.erase(key);
  }
}

CloudPtr VoxelSums::centroids() const {
  CloudPtr out(new Cloud);
  out->reserve(sums_.size());
  sums_.for_each([&out](uint64_t, const Sum& sum) {
    CloudPoint p;
    p.x = static_cast<float>(sum.x / sum.count);
    p.y = static_cast<float>(sum.y / sum.count);
    p.z = static_cast<float>(sum.z / sum.count);
    p.intensity = static_cast<float>(sum.intensity / sum.count);
    out->push_back(p);
  });
  return out;
}

CloudPtr voxel_filter(const Cloud& cloud, double leaf) {
  if (leaf <= 0.0 || cloud.empty()) return CloudPtr(new Cloud(cloud));
  VoxelSums sums(leaf);
  sums.add(cloud);
  return sums.centroids();
}

}  // namespace adaptive_lego_loam
