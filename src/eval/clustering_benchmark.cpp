#include "adaptive_lego_loam/eval/clustering_benchmark.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

bool is_blank(const std::string& line) {
  return line.find_first_not_of(" \t\r") == std::string::npos;
}

LabelledObject parse_label_line(const std::string& line, const std::string& where) {
  std::istringstream in(line);
  LabelledObject object;
  std::array<double, 3> centre{};
  int flag = 0;
  in >> object.object_class >> centre[0] >> centre[1] >> centre[2];
  for (double& value : object.box.min)
    in >> value;
  for (double& value : object.box.max)
    in >> value;
  in >> flag;
  std::string extra;
  if (!in || (in >> extra)) {
    throw IoError(where +
                  ": expected 'class cx cy cz x1 y1 z1 x2 y2 z2 flag' (a word, 9 numbers and an "
                  "integer)");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(object.box.min[axis]) || !std::isfinite(object.box.max[axis]) ||
        object.box.min[axis] > object.box.max[axis]) {
      throw IoError(where + ": box corners must be finite with min <= max on every axis");
    }
  }
  return object;
}

}  // namespace

double AxisAlignedBox::volume() const {
  return (max[0] - min[0]) * (max[1] - min[1]) * (max[2] - min[2]);
}

std::vector<LabelledObject> read_object_labels(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw IoError(path + ": cannot open label file");
  std::vector<LabelledObject> objects;
  std::string line;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    if (is_blank(line)) continue;
    objects.push_back(parse_label_line(line, path + ":" + std::to_string(line_number)));
  }
  if (file.bad()) throw IoError(path + ": read failed");
  return objects;
}

double iou_3d(const AxisAlignedBox& a, const AxisAlignedBox& b) {
  double intersection = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double overlap = std::min(a.max[axis], b.max[axis]) - std::max(a.min[axis], b.min[axis]);
    if (overlap <= 0.0) return 0.0;
    intersection *= overlap;
  }
  const double united = a.volume() + b.volume() - intersection;
  return united > 0.0 ? intersection / united : 0.0;
}

std::vector<AxisAlignedBox> cluster_boxes(const std::vector<ScanPoint>& points,
                                          const std::vector<int32_t>& cluster_of_point) {
  if (points.size() != cluster_of_point.size()) {
    throw std::invalid_argument("cluster_boxes: " + std::to_string(cluster_of_point.size()) +
                                " cluster ids for " + std::to_string(points.size()) + " points");
  }
  int32_t largest_id = -1;
  for (int32_t id : cluster_of_point)
    largest_id = std::max(largest_id, id);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<AxisAlignedBox> boxes(largest_id + 1, {{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}});
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (cluster_of_point[i] < 0) continue;
    AxisAlignedBox& box = boxes[cluster_of_point[i]];
    const std::array<double, 3> p{points[i].x, points[i].y, points[i].z};
    for (int axis = 0; axis < 3; ++axis) {
      box.min[axis] = std::min(box.min[axis], p[axis]);
      box.max[axis] = std::max(box.max[axis], p[axis]);
    }
  }
  // Ids that no point carries leave no box.
  boxes.erase(std::remove_if(boxes.begin(), boxes.end(),
                             [](const AxisAlignedBox& box) { return box.min[0] > box.max[0]; }),
              boxes.end());
  return boxes;
}

BestMatch best_match(const AxisAlignedBox& object, const std::vector<AxisAlignedBox>& clusters) {
  BestMatch best;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const double iou = iou_3d(object, clusters[i]);
    if (iou > best.iou) best = {iou, static_cast<int>(i)};
  }
  return best;
}

void PrecisionScore::add_frame(const std::vector<LabelledObject>& objects,
                               const std::vector<AxisAlignedBox>& clusters) {
  for (const LabelledObject& object : objects) {
    iou_sum_ += best_match(object.box, clusters).iou;
    ++objects_;
  }
  ++frames_;
}

}  // namespace adaptive_lego_loam
