#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {

void VoxelSums::add(const Cloud& points) {
  for (const CloudPoint& p : points) {
    Sum& sum = sums_.find_or_insert(voxel_key(p, inverse_leaf_));
    sum.x += p.x;
    sum.y += p.y;
    sum.z += p.z;
    sum.intensity += p.intensity;
    ++sum.count;
  }
}

void VoxelSums::reset(double leaf) {
  inverse_leaf_ = 1.0 / leaf;
  sums_.clear();
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

CloudPtr VoxelFilter::operator()(const Cloud& cloud, double leaf) {
  return (*this)(cloud, Cloud(), leaf);
}

CloudPtr VoxelFilter::operator()(const Cloud& cloud, const Cloud& more, double leaf) {
  if (leaf <= 0.0 || (cloud.empty() && more.empty())) {
    CloudPtr joined(new Cloud(cloud));
    *joined += more;
    return joined;
  }
  sums_.reset(leaf);
  sums_.add(cloud);
  sums_.add(more);
  return sums_.centroids();
}

CloudPtr voxel_filter(const Cloud& cloud, double leaf) {
  return VoxelFilter()(cloud, leaf);
}

}  // namespace adaptive_lego_loam
