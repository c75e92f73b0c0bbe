#include "adaptive_lego_loam/core/loop_closure/stepped_icp.h"

#include <pcl/registration/icp.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>

#include "adaptive_lego_loam/core/spatial/kdtree.h"

namespace adaptive_lego_loam {
namespace {

// PCL's KD-tree search answered by PointKdTree, which finds the same nearest points at the same
// squared distances (both sum dx^2 + dy^2 + dz^2 in float) in a third of the time and builds in
// half of it; only an exact tie may be broken differently. Serves ICP's correspondences and
// fitness, which only ask for the k nearest points of a point.
class PointKdTreeSearch : public pcl::search::KdTree<CloudPoint> {
 public:
  void setInputCloud(const PointCloudConstPtr& cloud,
                     const IndicesConstPtr& indices = IndicesConstPtr()) override {
    if (indices) throw std::invalid_argument("PointKdTreeSearch: indices are not supported");
    input_ = cloud;
    points_.build(cloud);
  }

  int nearestKSearch(const CloudPoint& point, int k, pcl::Indices& k_indices,
                     std::vector<float>& k_sqr_distances) const override {
    found_.resize(static_cast<std::size_t>(std::max(k, 0)));
    k_sqr_distances.resize(found_.size());
    const int count =
        points_.nearest(point.getVector3fMap(), k, found_.data(), k_sqr_distances.data());
    k_indices.assign(found_.begin(), found_.begin() + count);
    k_sqr_distances.resize(static_cast<std::size_t>(count));
    return count;
  }

  int radiusSearch(const CloudPoint&, double, pcl::Indices&, std::vector<float>&,
                   unsigned int) const override {
    throw std::logic_error("PointKdTreeSearch: radius search is not supported");
  }

 private:
  PointKdTree points_;
  mutable std::vector<uint32_t> found_;  // index buffer, kept to spare an allocation a query
};

Eigen::Isometry3d isometry(const Eigen::Matrix4f& transformation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.matrix() = transformation.cast<double>();
  return pose;
}

// PCL's point-to-point ICP one iteration per iterate(), the same iterations as one align() would
// run, bit for bit: each call aligns the cloud the previous one left (align() from the identity,
// not the original cloud moved by the product of the steps, which rounds differently), and the
// convergence criteria, which keep the previous iteration's MSE, are told that the end of a
// call is no convergence (otherwise they skip their checks there).
class PclSteppedIcp : public pcl::IterativeClosestPoint<CloudPoint, CloudPoint> {
 public:
  using State = pcl::registration::DefaultConvergenceCriteria<float>::ConvergenceState;

  PclSteppedIcp(CloudPtr source, const CloudPtr& target, double max_correspondence_distance)
      : source_(source), moved_(std::move(source)) {
    setMaxCorrespondenceDistance(max_correspondence_distance);
    setMaximumIterations(1);
    setTransformationEpsilon(1e-6);
    setEuclideanFitnessEpsilon(1e-6);
    setRANSACIterations(0);
    getConvergeCriteria()->setFailureAfterMaximumIterations(true);
    // Built once here; forced, so that no align() builds it again.
    auto tree = std::make_shared<PointKdTreeSearch>();
    tree->setInputCloud(target);
    setSearchMethodTarget(tree, true);
    setInputTarget(target);
  }

  void iterate() {
    setInputSource(moved_);
    CloudPtr moved(new Cloud);
    align(*moved);
    moved_ = std::move(moved);
    transformation_so_far_ = getFinalTransformation() * transformation_so_far_;
    ++iterations_;
  }

  int iterations() const { return iterations_; }
  bool found_no_correspondences() const {
    return state() == State::CONVERGENCE_CRITERIA_NO_CORRESPONDENCES;
  }
  // Met a tolerance (translation, rotation or MSE change).
  bool converged() const {
    return state() == State::CONVERGENCE_CRITERIA_TRANSFORM ||
           state() == State::CONVERGENCE_CRITERIA_ABS_MSE ||
           state() == State::CONVERGENCE_CRITERIA_REL_MSE;
  }
  const Matrix4& transformation() const { return transformation_so_far_; }

  // PCL's fitness (mean squared distance of every source point to its nearest target point)
  // of the source moved by every iteration so far, as align() would leave it.
  double fitness() {
    setInputSource(source_);
    final_transformation_ = transformation_so_far_;
    return getFitnessScore();
  }

  SteppedIcp::Inliers inliers(double max_distance) const {
    const CloudPtr moved = transform_cloud(*source_, isometry(transformation_so_far_));
    const float max_squared = static_cast<float>(max_distance * max_distance);
    pcl::Indices index(1);
    std::vector<float> squared(1);
    std::size_t count = 0;
    double sum = 0.0;
    for (const CloudPoint& p : *moved) {
      if (tree_->nearestKSearch(p, 1, index, squared) < 1 || squared[0] > max_squared) continue;
      ++count;
      sum += squared[0];
    }
    SteppedIcp::Inliers result;
    result.ratio = moved->empty() ? 0.0 : double(count) / moved->size();
    result.mean_squared_distance = count ? sum / count : std::numeric_limits<double>::infinity();
    return result;
  }

 private:
  State state() const { return convergence_criteria_->getConvergenceState(); }

  CloudPtr source_;  // as sampled
  CloudPtr moved_;   // as the last iteration left it
  Matrix4 transformation_so_far_ = Matrix4::Identity();
  int iterations_ = 0;
};

}  // namespace

struct SteppedIcp::Impl : PclSteppedIcp {
  using PclSteppedIcp::PclSteppedIcp;
};

SteppedIcp::SteppedIcp(CloudPtr source, const CloudPtr& target, const LoopClosureParams& params)
    : impl_(std::make_unique<Impl>(std::move(source), target,
                                   params.icp_max_correspondence_distance)) {}
SteppedIcp::~SteppedIcp() = default;

void SteppedIcp::iterate() {
  impl_->iterate();
}
int SteppedIcp::iterations() const {
  return impl_->iterations();
}
bool SteppedIcp::found_no_correspondences() const {
  return impl_->found_no_correspondences();
}
bool SteppedIcp::converged() const {
  return impl_->converged();
}
Eigen::Matrix4f SteppedIcp::transformation() const {
  return impl_->transformation();
}
double SteppedIcp::fitness() {
  return impl_->fitness();
}

SteppedIcp::Inliers SteppedIcp::inliers(double max_distance) const {
  return impl_->inliers(max_distance);
}

}  // namespace adaptive_lego_loam
