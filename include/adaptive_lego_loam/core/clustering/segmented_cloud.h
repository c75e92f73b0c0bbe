#pragma once
// The segmented cloud LeGO-LOAM's rules build from the depth clusters and the ground: what feature
// extraction reads, row by row, with its cloud info.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/cluster_labels.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

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

}  // namespace adaptive_lego_loam
