#include "adaptive_lego_loam/core/odometry/start_search.h"

namespace adaptive_lego_loam {

std::vector<Eigen::Isometry3d> start_guesses(const OdometryParams& params, double scan_period) {
  std::vector<Eigen::Isometry3d> guesses;
  const double reach = params.start_search_max_speed * scan_period;
  for (double x = 0.0; x <= reach + 1e-9; x += params.start_search_step) {
    Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
    guess.translation().x() = x;
    guesses.push_back(guess);
  }
  return guesses;
}

CloudPtr start_points(const std::vector<ScanPoint>& points, const std::vector<uint8_t>& ground_flag,
                      const std::vector<ScanPoint>& outliers) {
  CloudPtr cloud(new Cloud);
  cloud->reserve(points.size() + outliers.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i >= ground_flag.size() || !ground_flag[i])
      cloud->push_back(to_cloud_point(points[i], 0.f));
  }
  for (const ScanPoint& p : outliers)
    cloud->push_back(to_cloud_point(p, 0.f));
  return cloud;
}

double overlap_area(const PointKdTree& previous, const Cloud& points,
                    const Eigen::Isometry3d& motion, float radius) {
  if (previous.empty()) return 0.0;
  const Eigen::Isometry3f moved = motion.cast<float>();
  const float max_squared = radius * radius;
  double area = 0.0;
  uint32_t index;
  float squared;
  for (const CloudPoint& p : points) {
    const Eigen::Vector3f point = p.getVector3fMap();
    if (previous.nearest(moved * point, 1, &index, &squared, max_squared) > 0)
      area += point.squaredNorm();
  }
  return area;
}

}  // namespace adaptive_lego_loam
