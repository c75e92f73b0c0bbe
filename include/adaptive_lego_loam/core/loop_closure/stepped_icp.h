#pragma once
// PCL's point-to-point ICP run one iteration at a time, for a loop-closure attempt spread over
// scans: the same iterations as one align() would run, bit for bit. Its correspondences come from
// PointKdTree. PCL's registration headers stay in the source file.

#include <Eigen/Core>
#include <memory>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/common/params.h"

namespace adaptive_lego_loam {

class SteppedIcp {
 public:
  // Aligns `source` to `target` (whose KD-tree is built here) with params'
  // icp_max_correspondence_distance.
  SteppedIcp(CloudPtr source, const CloudPtr& target, const LoopClosureParams& params);
  ~SteppedIcp();
  SteppedIcp(const SteppedIcp&) = delete;
  SteppedIcp& operator=(const SteppedIcp&) = delete;

  void iterate();
  int iterations() const;
  bool found_no_correspondences() const;
  // Met a tolerance (translation, rotation or MSE change).
  bool converged() const;
  // Of every iteration so far.
  Eigen::Matrix4f transformation() const;
  // PCL's fitness (mean squared distance of every source point to its nearest target point) of
  // the source moved by every iteration so far, as align() would leave it.
  double fitness();

  struct Inliers {
    double ratio = 0.0;                  // of the source points
    double mean_squared_distance = 0.0;  // m^2, over the inliers (infinite without any)
  };
  // The source points within max_distance of the target, moved by every iteration so far.
  Inliers inliers(double max_distance) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptive_lego_loam
