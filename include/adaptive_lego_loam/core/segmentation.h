#pragma once
// LeGO-LOAM's imageProjection on the ROS-free core: projection (step 1), ground (step 2),
// depth clustering with one beta0 (step 3), and the segmented cloud with its CloudInfo.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/depth_clustering.h"
#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/range_image.h"
#include "adaptive_lego_loam/core/scan.h"
#include "adaptive_lego_loam/core/timing.h"

namespace adaptive_lego_loam {

// LeGO-LOAM's cloud_info, field for field (see msg/CloudInfo.msg).
struct CloudInfo {
  std::vector<int32_t> start_ring_index;
  std::vector<int32_t> end_ring_index;
  float start_orientation = 0.f;
  float end_orientation = 0.f;
  float orientation_diff = 0.f;
  std::vector<uint8_t> ground_flag;  // per segmented point
  std::vector<uint32_t> column;      // per segmented point
  std::vector<float> range;          // per segmented point
};

struct SegmentedCloud {
  std::vector<ScanPoint> points;  // kept cluster points and sub-sampled ground, row by row
  std::vector<uint16_t> row;      // per segmented point
  CloudInfo info;
  std::vector<ScanPoint> outliers;  // sub-sampled points of dropped clusters above ground rows
  std::vector<ScanPoint> ground;    // every ground point
};

// Fills `out` from labelled cells as LeGO-LOAM's cloudSegmentation does.
void build_segmented_cloud(const RangeImage& image, const std::vector<uint8_t>& ground,
                           const ClusterLabels& clusters, const SegmentationParams& params,
                           int ground_rows, SegmentedCloud& out);

// Azimuths of the first and last valid points, in LeGO-LOAM's clockwise convention.
void sweep_orientation(const Scan& scan, CloudInfo& info);

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
