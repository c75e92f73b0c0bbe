#pragma once
// The clustering benchmark of the paper's Table I (the KITTI part of Yang et al.'s LiDAR
// clustering benchmark): object boxes from label files, the axis-aligned box of every cluster a
// method outputs, and the precision: for every labelled box the best 3D IoU of any cluster box of
// its frame (0 if none), averaged over all labelled boxes of all frames.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

struct AxisAlignedBox {
  std::array<double, 3> min{};
  std::array<double, 3> max{};
  double volume() const;
};

struct LabelledObject {
  std::string object_class;
  AxisAlignedBox box;
};

// A label file: one object per line, `class cx cy cz x1 y1 z1 x2 y2 z2 flag`, x1..z2 the min and
// max corners of the object's box in the scan's frame (cx cy cz and flag are not used). Blank
// lines are skipped. Throws IoError naming file and line on a malformed line or unreadable file.
std::vector<LabelledObject> read_object_labels(const std::string& path);

// Intersection over union of two boxes; 0 when they do not overlap or both are empty.
double iou_3d(const AxisAlignedBox& a, const AxisAlignedBox& b);

// Per-point cluster id of a clustering: >= 0, or kUnclustered for a point in no output cluster.
constexpr int32_t kUnclustered = -1;

// The box of every cluster id that occurs in `cluster_of_point` (one entry per point of
// `points`), in increasing id order. Throws std::invalid_argument when the sizes differ.
std::vector<AxisAlignedBox> cluster_boxes(const std::vector<ScanPoint>& points,
                                          const std::vector<int32_t>& cluster_of_point);

// The best IoU of `object` with any of `clusters` (0 when there is none), and which one.
struct BestMatch {
  double iou = 0.0;
  int cluster = -1;  // index into the cluster boxes, -1 when none overlaps
};
BestMatch best_match(const AxisAlignedBox& object, const std::vector<AxisAlignedBox>& clusters);

// Accumulates the benchmark's precision over frames.
class PrecisionScore {
 public:
  // Adds one frame's labelled objects scored against its cluster boxes.
  void add_frame(const std::vector<LabelledObject>& objects,
                 const std::vector<AxisAlignedBox>& clusters);
  int objects() const { return objects_; }
  int frames() const { return frames_; }
  // Mean best IoU over every object added, in [0, 1]; 0 when no object was added.
  double precision() const { return objects_ > 0 ? iou_sum_ / objects_ : 0.0; }

 private:
  double iou_sum_ = 0.0;
  int objects_ = 0;
  int frames_ = 0;
};

}  // namespace adaptive_lego_loam
