#include "adaptive_lego_loam/core/kdtree.h"

#include <nanoflann.hpp>

namespace adaptive_lego_loam {
namespace {

struct CloudAdaptor {
  const Cloud* cloud = nullptr;
  std::size_t kdtree_get_point_count() const { return cloud->size(); }
  float kdtree_get_pt(std::size_t index, std::size_t dim) const {
    return (*cloud)[index].data[dim];
  }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>,
                                                 CloudAdaptor, 3, uint32_t>;

}  // namespace

struct PointKdTree::Index {
  CloudAdaptor adaptor;
  Tree tree;
  explicit Index(const Cloud* cloud)
      : adaptor{cloud}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
  }
};

PointKdTree::PointKdTree() = default;
PointKdTree::~PointKdTree() = default;
PointKdTree::PointKdTree(PointKdTree&&) noexcept = default;
PointKdTree& PointKdTree::operator=(PointKdTree&&) noexcept = default;

void PointKdTree::build(CloudConstPtr cloud) {
  cloud_ = std::move(cloud);
  index_.reset();
  if (cloud_ && !cloud_->empty()) index_ = std::make_unique<Index>(cloud_.get());
}

int PointKdTree::nearest(const Eigen::Vector3f& query, int k, uint32_t* indices,
                         float* squared_distances) const {
  if (!index_) return 0;
  nanoflann::KNNResultSet<float, uint32_t> result(static_cast<uint32_t>(k));
  result.init(indices, squared_distances);
  index_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
  return static_cast<int>(result.size());
}

bool PointKdTree::empty() const {
  return !index_;
}

}  // namespace adaptive_lego_loam
