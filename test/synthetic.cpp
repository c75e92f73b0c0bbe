#include "synthetic.h"

#include <cmath>
#include <limits>

namespace adaptive_lego_loam::test {

SensorParams even_sensor(int rows, int cols, double vertical_min_deg, double vertical_max_deg) {
  SensorParams sensor;
  sensor.name = "synthetic";
  sensor.rows = rows;
  sensor.columns = cols;
  sensor.row_source = RowSource::kRing;
  for (int row = 0; row < rows; ++row) {
    sensor.beam_angles_deg.push_back(vertical_min_deg +
                                     (vertical_max_deg - vertical_min_deg) * row / (rows - 1));
  }
  sensor.min_range = 0.5;
  sensor.max_range = 100.0;
  sensor.ground_rows = rows / 2;
  return sensor;
}

Eigen::Vector3d beam_direction(const SensorParams& sensor, int row, int col) {
  // Column 0 starts at azimuth -pi (looking along -x); see RangeProjector.
  const double azimuth = (col + 0.5) * 2.0 * M_PI / sensor.columns - M_PI;
  const double elevation = sensor.beam_angles_deg[row] * M_PI / 180.0;
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

ScanPoint cell_point(const SensorParams& sensor, int row, int col, double range) {
  const Eigen::Vector3d p = beam_direction(sensor, row, col) * range;
  ScanPoint point;
  point.x = static_cast<float>(p.x());
  point.y = static_cast<float>(p.y());
  point.z = static_cast<float>(p.z());
  point.ring = row;
  return point;
}

namespace {

// Slab test: distance along `dir` to the box, or infinity.
double hit_box(const Box& box, const Eigen::Vector3d& dir) {
  double near = 0.0, far = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (std::fabs(dir[axis]) < 1e-12) {
      if (0.0 < box.min[axis] || 0.0 > box.max[axis]) return far;
      continue;
    }
    double t0 = box.min[axis] / dir[axis], t1 = box.max[axis] / dir[axis];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) return std::numeric_limits<double>::infinity();
  }
  return near > 0.0 ? near : std::numeric_limits<double>::infinity();
}

}  // namespace

Scan render(const SensorParams& sensor, const Scene& scene) {
  Scan scan;
  scan.has_ring = true;
  for (int row = 0; row < sensor.rows; ++row) {
    for (int col = 0; col < sensor.columns; ++col) {
      const Eigen::Vector3d dir = beam_direction(sensor, row, col);
      double range = std::numeric_limits<double>::infinity();
      for (const Box& box : scene.boxes)
        range = std::min(range, hit_box(box, dir));
      if (scene.has_ground && dir.z() < 0.0) range = std::min(range, scene.ground_z / dir.z());
      if (range <= sensor.max_range) scan.points.push_back(cell_point(sensor, row, col, range));
    }
  }
  return scan;
}

}  // namespace adaptive_lego_loam::test
