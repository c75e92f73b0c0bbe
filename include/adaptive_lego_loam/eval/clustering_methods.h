#pragma once
// The six clustering methods of the paper's Table I, run on one ground-free scan each and giving
// a cluster id per input point.
//
// Range-image methods (adaptive, ccl_euclidean, depth, run) cluster the cells of the scan's range
// image. A point the projection drops (out of range, outside the beams, non-finite, or lost to a
// cell already taken) is in no cluster (kUnclustered): it adds no box. The same holds for DBSCAN's
// noise and for every cluster smaller than the benchmark's minimum size.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

enum class ClusteringMethod { kAdaptive, kCclEuclidean, kDepth, kRun, kEuclideanKdtree, kDbscan };

// Every method, in the order of the benchmark's table.
const std::vector<ClusteringMethod>& all_clustering_methods();
std::string method_name(ClusteringMethod method);
std::optional<ClusteringMethod> method_from_name(const std::string& name);
bool uses_range_image(ClusteringMethod method);

// The baselines' parameters, the paper's values by default. The adaptive method and the
// fixed-threshold range-image method take their window (and gamma) from the config's
// ambient_filter section.
struct BaselineParams {
  double ccl_threshold_m = 0.75;   // ccl_euclidean: fixed distance on the range image
  double depth_beta0_deg = 10.0;   // depth
  double run_threshold_m = 0.5;    // run: th_run
  double merge_threshold_m = 1.0;  // run: th_merge
  double kdtree_eps_m = 0.75;      // euclidean_kdtree: cluster tolerance
  double dbscan_eps_m = 0.75;      // dbscan
  int dbscan_min_samples = 5;
};

struct ScanClustering {
  std::vector<int32_t> cluster_of_point;  // one per input point: id >= 0 or kUnclustered
  int clusters = 0;                       // ids 0 .. clusters - 1, each with min_points or more
  int unclustered_points = 0;
  int dropped_by_projection = 0;  // range-image methods: input points without a cell
  // Preparation: the range-image projection, or copying the scan into a PCL cloud (dbscan
  // copies it inside its clustering time).
  double preparation_ms = 0.0;
  // The clustering alone (for the KD-tree methods, building the tree included).
  double clustering_ms = 0.0;
};

class ClusteringRunner {
 public:
  // Throws ConfigError when the config's sensor cannot be projected.
  ClusteringRunner(ClusteringMethod method, const Config& config,
                   const BaselineParams& baselines = {});
  ~ClusteringRunner();
  ClusteringRunner(const ClusteringRunner&) = delete;
  ClusteringRunner& operator=(const ClusteringRunner&) = delete;

  ClusteringMethod method() const { return method_; }
  void cluster(const Scan& scan, ScanClustering& out);

 private:
  struct State;
  ClusteringMethod method_;
  int min_cluster_points_;
  std::unique_ptr<State> state_;
};

}  // namespace adaptive_lego_loam
