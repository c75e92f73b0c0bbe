#pragma once
// The ambient-aware filter, docs/METHOD.md steps 1-9: range image and ground, adaptive Euclidean
// and strict depth clustering, their intersection (the skeleton), normals of the skeleton, the
// degeneration degree mu, beta0 from mu, and the final depth clustering that cleans the scan.
// In fixed mode steps 4-8 are skipped and beta0 is the configured one: LeGO-LOAM's behaviour.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/ambient/degeneration.h"
#include "adaptive_lego_loam/core/ambient/skeleton_normals.h"
#include "adaptive_lego_loam/core/clustering/depth_clustering.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"

namespace adaptive_lego_loam {

struct AmbientFilterResult {
  // Range image, ground, the final depth clusters, the clean (segmented) cloud and every
  // stage's time.
  SegmentationResult segmentation;
  ClusterLabels euclidean;        // step 4
  ClusterLabels skeleton_depth;   // step 5: depth clusters at beta0_max
  std::vector<uint8_t> skeleton;  // per cell
  int skeleton_points = 0;
  int euclidean_points = 0;          // non-ground points in step 4's kept clusters
  double fragment_smoothness = 0.0;  // fragment_smoothness() of step 4's and 5's labels
  double structure_share = 0.0;      // structure_share(): the skeleton and smooth fragments
  std::vector<NormalFeature> normals;
  Degeneration degeneration;  // of this scan alone; degeneration.valid = false: mu unknown
  double mu = 0.0;            // after smoothing; the previous value when this scan's is unknown
  double beta0_deg = 0.0;     // threshold that cleaned this scan
  bool every_cluster_kept = false;  // the size rule was off: mode none, or mu_keep_every_cluster
  bool adaptive = true;

  std::vector<ScanPoint> skeleton_cloud() const;
  // The skeleton's points over the kept Euclidean clusters' points (0 without any).
  double skeleton_share() const;
  const StageTimes& times() const { return segmentation.times; }
};

EuclideanClusteringParams euclidean_params(const AmbientFilterParams& ambient, int min_points);
NormalParams normal_params(const AmbientFilterParams& ambient, double max_range);

class AmbientFilter {
 public:
  explicit AmbientFilter(const Config& config);
  void process(const Scan& scan, AmbientFilterResult& result);
  // Forgets the previous scans' mu and beta0 (start of a new sequence).
  void reset();

  const Config& config() const { return config_; }
  const Segmenter& segmenter() const { return segmenter_; }

 private:
  void estimate_degeneration(AmbientFilterResult& result);

  Config config_;
  Segmenter segmenter_;
  EuclideanClustering euclidean_;
  DepthClustering strict_depth_;  // step 5 at beta0_max, then step 9 merging its clusters
  bool has_previous_ = false;
  double previous_mu_ = 0.0;
  double previous_beta0_deg_ = 0.0;
};

}  // namespace adaptive_lego_loam
