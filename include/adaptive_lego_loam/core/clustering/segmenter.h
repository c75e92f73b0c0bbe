#pragma once
// LeGO-LOAM's imageProjection on the ROS-free core: projection (step 1), ground (step 2),
// depth clustering with one beta0 (step 3), and the segmented cloud with its CloudInfo.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/depth_clustering.h"
#include "adaptive_lego_loam/core/clustering/segmented_cloud.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

struct SegmentationResult {
  RangeImage image;
  std::vector<uint8_t> ground;  // per cell
  int ground_points = 0;
  ClusterLabels clusters;
  double beta0_deg = 0.0;  // the threshold the clusters were made with
  SegmentedCloud cloud;
  StageTimes times;
};

class Segmenter {
 public:
  Segmenter(const SensorParams& sensor, const SegmentationParams& params);

  // Steps 1-3 with the configured beta0, then the segmented cloud.
  void process(const Scan& scan, SegmentationResult& result);

  // The parts, for the ambient filter which picks beta0 in between.
  void project_and_mark_ground(const Scan& scan, SegmentationResult& result);
  void cluster_and_build(const Scan& scan, double beta0_deg, SegmentationResult& result);
  // The segmented cloud from result.clusters (made with result.beta0_deg).
  void build_cloud(const Scan& scan, SegmentationResult& result) const;

  const SensorParams& sensor() const { return sensor_; }
  const SegmentationParams& params() const { return params_; }
  const RangeImageGeometry& geometry() const { return projector_.geometry(); }

 private:
  SensorParams sensor_;
  SegmentationParams params_;
  RangeProjector projector_;
  DepthClustering depth_;
};

}  // namespace adaptive_lego_loam
