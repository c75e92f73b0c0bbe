#include "adaptive_lego_loam/core/ambient/ambient_filter.h"

#include <climits>

#include "adaptive_lego_loam/core/ambient/skeleton.h"

namespace adaptive_lego_loam {

EuclideanClusteringParams euclidean_params(const AmbientFilterParams& ambient, int min_points) {
  EuclideanClusteringParams params;
  params.window = ambient.euclidean_window;
  params.gamma = ambient.euclidean_gamma;
  params.fixed_threshold = ambient.euclidean_fixed_threshold;
  params.criterion = ambient.euclidean_criterion;
  params.min_points = min_points;
  return params;
}

NormalParams normal_params(const AmbientFilterParams& ambient, double max_range) {
  NormalParams params;
  params.sample_ratio = ambient.normal_sample_ratio;
  params.window = ambient.normal_window;
  params.depth_threshold = ambient.normal_depth_threshold;
  params.min_neighbors = ambient.normal_min_neighbors;
  params.max_range = max_range;
  params.seed = ambient.seed;
  return params;
}

std::vector<ScanPoint> AmbientFilterResult::skeleton_cloud() const {
  std::vector<ScanPoint> points;
  points.reserve(skeleton_points);
  const RangeImage& image = segmentation.image;
  for (int cell = 0; cell < static_cast<int>(skeleton.size()); ++cell) {
    if (skeleton[cell]) points.push_back(image.point(cell));
  }
  return points;
}

double AmbientFilterResult::skeleton_share() const {
  return euclidean_points > 0 ? static_cast<double>(skeleton_points) / euclidean_points : 0.0;
}

namespace {

constexpr ClusterSizeRule kKeepEveryCluster{1, 1, 1};

// Without segmentation every cluster is kept, however small.
SegmentationParams segmentation_params(const Config& config) {
  SegmentationParams params = config.segmentation;
  if (config.ambient.mode == Beta0Mode::kNone) params.size_rule = kKeepEveryCluster;
  return params;
}

}  // namespace

AmbientFilter::AmbientFilter(const Config& config)
    : config_(config),
      segmenter_(config.sensor, segmentation_params(config)),
      euclidean_(segmenter_.geometry(),
                 euclidean_params(config.ambient, config.ambient.skeleton_euclidean_min_points)),
      strict_depth_(segmenter_.geometry()) {}

void AmbientFilter::reset() {
  has_previous_ = false;
  previous_mu_ = 0.0;
  previous_beta0_deg_ = 0.0;
}

void AmbientFilter::process(const Scan& scan, AmbientFilterResult& result) {
  const AmbientFilterParams& ambient = config_.ambient;
  segmenter_.project_and_mark_ground(scan, result.segmentation);
  result.adaptive = ambient.mode == Beta0Mode::kAdaptive;
  if (!result.adaptive) {
    result.degeneration = Degeneration();
    result.skeleton_points = 0;
    result.euclidean_points = 0;
    result.fragment_smoothness = 0.0;
    result.structure_share = 0.0;
    result.normals.clear();
    result.mu = 0.0;
    result.beta0_deg = ambient.mode == Beta0Mode::kNone ? 0.0 : ambient.fixed_beta0_deg;
    result.every_cluster_kept = ambient.mode == Beta0Mode::kNone;
    segmenter_.cluster_and_build(scan, result.beta0_deg, result.segmentation);
    return;
  }
  estimate_degeneration(result);
  // Step 9 from step 5's strict clusters: with beta0 below the skeleton's threshold the clusters
  // only merge (recluster() handles either way).
  SegmentationResult& segmentation = result.segmentation;
  Stopwatch watch;
  // A sparse sensor in a degenerate scene sees its few constraining objects (posts, distant
  // poles) as clusters below the size rule: from mu_keep_every_cluster on they stay.
  result.every_cluster_kept = result.mu >= ambient.mu_keep_every_cluster;
  strict_depth_.recluster(
      segmentation.image, result.beta0_deg,
      result.every_cluster_kept ? kKeepEveryCluster : segmenter_.params().size_rule,
      segmentation.clusters);
  segmentation.beta0_deg = result.beta0_deg;
  segmentation.times.add("depth_clustering", watch.lap_ms());
  segmenter_.build_cloud(scan, segmentation);
}

void AmbientFilter::estimate_degeneration(AmbientFilterResult& result) {
  const AmbientFilterParams& ambient = config_.ambient;
  SegmentationResult& segmentation = result.segmentation;
  const RangeImage& image = segmentation.image;
  StageTimes& times = segmentation.times;
  Stopwatch watch;

  euclidean_.cluster(image, segmentation.ground, result.euclidean);
  times.add("euclidean_clustering", watch.lap_ms());

  // Surfaces: depth clusters at the strict threshold, kept on size alone.
  const ClusterSizeRule surface_rule{ambient.skeleton_depth_min_points, INT_MAX, INT_MAX};
  strict_depth_.cluster(image, segmentation.ground, ambient.skeleton_beta0_deg, surface_rule,
                        result.skeleton_depth);
  result.skeleton_points =
      extract_skeleton(result.euclidean, result.skeleton_depth, result.skeleton);
  result.euclidean_points = result.euclidean.kept_points();
  result.fragment_smoothness = fragment_smoothness(image, result.euclidean, result.skeleton,
                                                   ambient.fragment_smooth_tolerance_m);
  times.add("skeleton", watch.lap_ms());

  compute_normals(image, result.skeleton, segmentation.ground,
                  normal_params(ambient, config_.sensor.max_range), result.normals);
  times.add("normals", watch.lap_ms());

  result.structure_share =
      structure_share(result.skeleton_points, result.euclidean_points, result.fragment_smoothness,
                      ambient.fragment_smoothness_floor);
  result.degeneration = degeneration_from_normals(result.normals);
  if (result.degeneration.valid) {
    const double raw = mu_with_structure(
        mu_with_evidence(result.degeneration.mu, result.degeneration.normals,
                         ambient.mu_evidence_normals),
        result.structure_share, ambient.mu_structure_weight, ambient.mu_structure_reference);
    const double smoothing = has_previous_ ? ambient.mu_smoothing : 0.0;
    result.mu = smoothing * previous_mu_ + (1.0 - smoothing) * raw;
    result.beta0_deg = beta0_from_mu(result.mu, ambient.beta0_min_deg, ambient.beta0_max_deg,
                                     ambient.mu_strict_below, ambient.mu_lenient_above);
    has_previous_ = true;
    previous_mu_ = result.mu;
    previous_beta0_deg_ = result.beta0_deg;
  } else if (has_previous_) {
    // No skeleton normal (empty or all-ground scan): keep the last threshold.
    result.mu = previous_mu_;
    result.beta0_deg = previous_beta0_deg_;
  } else {
    result.mu = 0.0;
    result.beta0_deg = ambient.beta0_max_deg;  // LeGO-LOAM's strict default until mu is known
  }
  times.add("degeneration", watch.lap_ms());
}

}  // namespace adaptive_lego_loam
