#include "adaptive_lego_loam/eval/clustering_methods.h"

#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/clustering/dbscan.h"
#include "adaptive_lego_loam/core/clustering/depth_clustering.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/core/clustering/run_clustering.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "adaptive_lego_loam/eval/clustering_benchmark.h"

namespace adaptive_lego_loam {
namespace {

const std::vector<std::pair<ClusteringMethod, std::string>>& method_table() {
  static const std::vector<std::pair<ClusteringMethod, std::string>> table = {
      {ClusteringMethod::kAdaptive, "adaptive"},
      {ClusteringMethod::kCclEuclidean, "ccl_euclidean"},
      {ClusteringMethod::kDepth, "depth"},
      {ClusteringMethod::kRun, "run"},
      {ClusteringMethod::kEuclideanKdtree, "euclidean_kdtree"},
      {ClusteringMethod::kDbscan, "dbscan"}};
  return table;
}

// The filter's step-4 params (window, gamma) with the given threshold: 0 adaptive, else fixed.
EuclideanClusteringParams range_image_euclidean_params(const AmbientFilterParams& ambient,
                                                       double fixed_threshold) {
  EuclideanClusteringParams params = euclidean_params(ambient, 1);
  params.fixed_threshold = fixed_threshold;
  return params;
}

// Renumbers the raw ids of `ids` densely from 0, dropping clusters below min_points.
void keep_clusters_of_min_size(std::vector<int32_t>& ids, int min_points, ScanClustering& out) {
  int32_t largest = -1;
  for (int32_t id : ids)
    largest = std::max(largest, id);
  std::vector<int32_t> size(largest + 1, 0);
  for (int32_t id : ids)
    if (id >= 0) ++size[id];
  std::vector<int32_t> new_id(largest + 1, kUnclustered);
  out.clusters = 0;
  for (int32_t id = 0; id <= largest; ++id) {
    if (size[id] > 0 && size[id] >= min_points) new_id[id] = out.clusters++;
  }
  out.unclustered_points = 0;
  for (int32_t& id : ids) {
    id = id >= 0 ? new_id[id] : kUnclustered;
    out.unclustered_points += id == kUnclustered;
  }
}

pcl::PointCloud<pcl::PointXYZ>::Ptr finite_cloud(const Scan& scan, std::vector<int>& source) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(scan.points.size());
  source.clear();
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const ScanPoint& p = scan.points[i];
    if (!std::isfinite(p.x + p.y + p.z)) continue;
    cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
    source.push_back(static_cast<int>(i));
  }
  return cloud;
}

}  // namespace

const std::vector<ClusteringMethod>& all_clustering_methods() {
  static const std::vector<ClusteringMethod> methods = [] {
    std::vector<ClusteringMethod> list;
    for (const auto& entry : method_table())
      list.push_back(entry.first);
    return list;
  }();
  return methods;
}

std::string method_name(ClusteringMethod method) {
  for (const auto& [candidate, name] : method_table())
    if (candidate == method) return name;
  return "unknown";
}

std::optional<ClusteringMethod> method_from_name(const std::string& name) {
  for (const auto& [method, candidate] : method_table())
    if (candidate == name) return method;
  return std::nullopt;
}

bool uses_range_image(ClusteringMethod method) {
  return method == ClusteringMethod::kAdaptive || method == ClusteringMethod::kCclEuclidean ||
         method == ClusteringMethod::kDepth || method == ClusteringMethod::kRun;
}

struct ClusteringRunner::State {
  BaselineParams baselines;
  // Range-image methods.
  std::unique_ptr<RangeProjector> projector;
  RangeImage image;
  ClusterLabels labels;
  std::unique_ptr<EuclideanClustering> euclidean;
  std::unique_ptr<DepthClustering> depth;
  std::unique_ptr<RunClustering> run;
  // Point methods: the finite points' indices in the scan.
  std::vector<int> source;

  void cluster_range_image(ClusteringMethod method, const Scan& scan, std::vector<int32_t>& ids,
                           ScanClustering& out);
  void cluster_kdtree_euclidean(const Scan& scan, std::vector<int32_t>& ids, ScanClustering& out);
  void cluster_dbscan(const Scan& scan, std::vector<int32_t>& ids, ScanClustering& out);
};

void ClusteringRunner::State::cluster_range_image(ClusteringMethod method, const Scan& scan,
                                                  std::vector<int32_t>& ids, ScanClustering& out) {
  Stopwatch watch;
  projector->project(scan, image);
  out.preparation_ms = watch.lap_ms();
  switch (method) {
    case ClusteringMethod::kAdaptive:
    case ClusteringMethod::kCclEuclidean:
      euclidean->cluster(image, {}, labels);
      break;
    case ClusteringMethod::kDepth:
      depth->cluster(image, {}, baselines.depth_beta0_deg, ClusterSizeRule{1, 1, 1}, labels);
      break;
    case ClusteringMethod::kRun:
      run->cluster(image, {}, labels);
      break;
    default:
      throw std::logic_error("not a range-image method");
  }
  out.clustering_ms = watch.lap_ms();
  out.dropped_by_projection = image.stats().input_points - image.stats().projected;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (image.occupied(cell) && labels.label[cell] != ClusterLabels::kNone) {
      ids[image.source_index(cell)] = labels.label[cell] - 1;
    }
  }
}

void ClusteringRunner::State::cluster_kdtree_euclidean(const Scan& scan, std::vector<int32_t>& ids,
                                                       ScanClustering& out) {
  Stopwatch watch;
  const auto cloud = finite_cloud(scan, source);
  out.preparation_ms = watch.lap_ms();
  if (cloud->empty()) return;
  // extract() builds the tree on its input: that build is counted as clustering time.
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>(false));
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
  extraction.setClusterTolerance(baselines.kdtree_eps_m);
  extraction.setMinClusterSize(1);  // the benchmark's minimum applies to every method alike
  extraction.setMaxClusterSize(std::numeric_limits<int>::max());
  extraction.setSearchMethod(tree);
  extraction.setInputCloud(cloud);
  std::vector<pcl::PointIndices> clusters;
  extraction.extract(clusters);
  out.clustering_ms = watch.lap_ms();
  for (std::size_t id = 0; id < clusters.size(); ++id) {
    for (int index : clusters[id].indices)
      ids[source[index]] = static_cast<int32_t>(id);
  }
}

void ClusteringRunner::State::cluster_dbscan(const Scan& scan, std::vector<int32_t>& ids,
                                             ScanClustering& out) {
  Stopwatch watch;
  // dbscan() builds its own tree from the points: all of it is clustering time.
  const std::vector<int32_t> labels =
      dbscan(scan.points, {baselines.dbscan_eps_m, baselines.dbscan_min_samples});
  out.clustering_ms = watch.lap_ms();
  for (std::size_t i = 0; i < labels.size(); ++i)
    ids[i] = labels[i] == kDbscanNoise ? kUnclustered : labels[i];
}

ClusteringRunner::ClusteringRunner(ClusteringMethod method, const Config& config,
                                   const BaselineParams& baselines)
    : method_(method),
      min_cluster_points_(config.clustering_benchmark.min_cluster_points),
      state_(std::make_unique<State>()) {
  state_->baselines = baselines;
  if (!uses_range_image(method)) return;
  state_->projector = std::make_unique<RangeProjector>(config.sensor);
  const RangeImageGeometry& geometry = state_->projector->geometry();
  switch (method) {
    case ClusteringMethod::kAdaptive:
      state_->euclidean = std::make_unique<EuclideanClustering>(
          geometry, range_image_euclidean_params(config.ambient, 0.0));
      break;
    case ClusteringMethod::kCclEuclidean:
      state_->euclidean = std::make_unique<EuclideanClustering>(
          geometry, range_image_euclidean_params(config.ambient, baselines.ccl_threshold_m));
      break;
    case ClusteringMethod::kDepth:
      state_->depth = std::make_unique<DepthClustering>(geometry);
      break;
    default:
      state_->run = std::make_unique<RunClustering>(
          geometry, RunClusteringParams{baselines.run_threshold_m, baselines.merge_threshold_m, 1});
  }
}

ClusteringRunner::~ClusteringRunner() = default;

void ClusteringRunner::cluster(const Scan& scan, ScanClustering& out) {
  out = ScanClustering();
  std::vector<int32_t>& ids = out.cluster_of_point;
  ids.assign(scan.points.size(), kUnclustered);
  if (uses_range_image(method_)) {
    state_->cluster_range_image(method_, scan, ids, out);
  } else if (method_ == ClusteringMethod::kEuclideanKdtree) {
    state_->cluster_kdtree_euclidean(scan, ids, out);
  } else {
    state_->cluster_dbscan(scan, ids, out);
  }
  keep_clusters_of_min_size(ids, min_cluster_points_, out);
}

}  // namespace adaptive_lego_loam
