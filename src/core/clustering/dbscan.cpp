#include "adaptive_lego_loam/core/clustering/dbscan.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <cmath>

namespace adaptive_lego_loam {
namespace {

constexpr int32_t kUnvisited = -2;

}  // namespace

std::vector<int32_t> dbscan(const std::vector<ScanPoint>& points, const DbscanParams& params) {
  std::vector<int32_t> label(points.size(), kDbscanNoise);
  // The tree holds the finite points only; `source` maps its indices back.
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  std::vector<int> source;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ScanPoint& p = points[i];
    if (!std::isfinite(p.x + p.y + p.z)) continue;
    cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
    source.push_back(static_cast<int>(i));
  }
  if (cloud->empty()) return label;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree(/*sorted=*/false);
  tree.setInputCloud(cloud);

  std::vector<int32_t> tree_label(cloud->size(), kUnvisited);
  std::vector<int> neighbours, queue;
  std::vector<float> squared_distances;
  auto neighbourhood = [&](int index) {
    tree.radiusSearch(index, params.eps, neighbours, squared_distances);
    return static_cast<int>(neighbours.size());
  };
  int32_t next_id = 0;
  for (int seed = 0; seed < static_cast<int>(cloud->size()); ++seed) {
    if (tree_label[seed] != kUnvisited) continue;
    if (neighbourhood(seed) < params.min_samples) {
      tree_label[seed] = kDbscanNoise;  // may still become a border point of a later cluster
      continue;
    }
    const int32_t id = next_id++;
    tree_label[seed] = id;
    // A point is labelled when first reached, so it is queued at most once. Noise found earlier
    // is not a core point: it becomes a border point of this cluster without being expanded.
    queue.clear();
    auto absorb_neighbours = [&]() {
      for (int index : neighbours) {
        if (tree_label[index] == kUnvisited) {
          tree_label[index] = id;
          queue.push_back(index);
        } else if (tree_label[index] == kDbscanNoise) {
          tree_label[index] = id;
        }
      }
    };
    absorb_neighbours();
    for (std::size_t head = 0; head < queue.size(); ++head) {
      if (neighbourhood(queue[head]) >= params.min_samples) absorb_neighbours();
    }
  }
  for (std::size_t i = 0; i < source.size(); ++i)
    label[source[i]] = tree_label[i];
  return label;
}

}  // namespace adaptive_lego_loam
