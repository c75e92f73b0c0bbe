#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <cmath>

namespace adaptive_lego_loam {

KdTreeNormalParams kdtree_normal_params(const Config& config) {
  KdTreeNormalParams params;
  params.radius = config.ambient.normal_depth_threshold;
  params.min_neighbors = config.ambient.normal_min_neighbors;
  params.max_range = config.sensor.max_range;
  return params;
}

std::vector<ScanPoint> non_ground_points(const SegmentationResult& segmentation) {
  std::vector<ScanPoint> points;
  const RangeImage& image = segmentation.image;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (image.occupied(cell) && !segmentation.ground[cell]) points.push_back(image.point(cell));
  }
  return points;
}

void kdtree_normals(const std::vector<ScanPoint>& points, const KdTreeNormalParams& params,
                    std::vector<NormalFeature>& normals) {
  normals.clear();
  if (points.empty()) return;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(points.size());
  for (const ScanPoint& p : points)
    cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<int> indices;
  std::vector<float> squared_distances;
  std::vector<Eigen::Vector3f> neighbourhood;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const int count = tree.radiusSearch((*cloud)[i], params.radius, indices, squared_distances);
    if (count < params.min_neighbors) continue;
    neighbourhood.clear();
    for (int index : indices)
      neighbourhood.push_back((*cloud)[index].getVector3fMap());
    NormalFeature feature;
    if (!pca_normal(neighbourhood, feature.normal)) continue;
    const ScanPoint& p = points[i];
    const double range = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
    feature.weight = normal_weight(params.max_range, range, count);
    feature.neighbors = count;
    normals.push_back(feature);
  }
}

}  // namespace adaptive_lego_loam
