#include "support/synthetic.h"

#include <cmath>
#include <limits>

#include "adaptive_lego_loam/core/odometry/deskew.h"

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

void add_scatter(const SensorParams& sensor, int row_begin, int row_end, int col_begin, int col_end,
                 double range_m, double depth_m, std::mt19937& rng, Scan& scan) {
  std::uniform_real_distribution<double> depth(0.0, depth_m);
  for (int row = row_begin; row < row_end; ++row) {
    for (int col = col_begin; col < col_end; ++col) {
      const int wrapped = (col % sensor.columns + sensor.columns) % sensor.columns;
      scan.points.push_back(cell_point(sensor, row, wrapped, range_m + depth(rng)));
    }
  }
}

namespace {

// Slab test: distance along `dir` from `origin` to the box, or infinity.
double hit_box(const Box& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  double near = 0.0, far = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (std::fabs(dir[axis]) < 1e-12) {
      if (origin[axis] < box.min[axis] || origin[axis] > box.max[axis]) return far;
      continue;
    }
    double t0 = (box.min[axis] - origin[axis]) / dir[axis];
    double t1 = (box.max[axis] - origin[axis]) / dir[axis];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) return std::numeric_limits<double>::infinity();
  }
  return near > 0.0 ? near : std::numeric_limits<double>::infinity();
}

// Range along the beam of (row, col) of a sensor at `pose`, or infinity.
double cast(const SensorParams& sensor, const Scene& scene, const Eigen::Isometry3d& pose, int row,
            int col) {
  const Eigen::Vector3d origin = pose.translation();
  const Eigen::Vector3d dir = pose.linear() * beam_direction(sensor, row, col);
  double range = std::numeric_limits<double>::infinity();
  for (const Box& box : scene.boxes)
    range = std::min(range, hit_box(box, origin, dir));
  if (scene.has_ground && dir.z() < 0.0) {
    range = std::min(range, (scene.ground_z - origin.z()) / dir.z());
  }
  return range <= sensor.max_range ? range : std::numeric_limits<double>::infinity();
}

}  // namespace

Scan render(const SensorParams& sensor, const Scene& scene) {
  return render(sensor, scene, Eigen::Isometry3d::Identity());
}

Scan render(const SensorParams& sensor, const Scene& scene, const Eigen::Isometry3d& sensor_pose) {
  Scan scan;
  scan.has_ring = true;
  for (int row = 0; row < sensor.rows; ++row) {
    for (int col = 0; col < sensor.columns; ++col) {
      const double range = cast(sensor, scene, sensor_pose, row, col);
      if (std::isfinite(range)) scan.points.push_back(cell_point(sensor, row, col, range));
    }
  }
  return scan;
}

Scan render_sweep(const SensorParams& sensor, const Scene& scene, const Eigen::Isometry3d& start,
                  const Eigen::Isometry3d& sweep_motion, std::vector<Eigen::Vector3d>& world_hits) {
  return render_sweep(
      sensor, scene,
      [&](double fraction) { return start * interpolate_motion(sweep_motion, fraction); },
      world_hits);
}

Scan render_sweep(const SensorParams& sensor, const Scene& scene,
                  const std::function<Eigen::Isometry3d(double)>& pose_at,
                  std::vector<Eigen::Vector3d>& world_hits) {
  Scan scan;
  scan.has_ring = true;
  scan.has_time = true;
  world_hits.clear();
  for (int fired = 0; fired < sensor.columns; ++fired) {
    const int col = sensor.columns - 1 - fired;
    const double fraction = double(fired) / sensor.columns;
    const Eigen::Isometry3d pose = pose_at(fraction);
    for (int row = 0; row < sensor.rows; ++row) {
      const double range = cast(sensor, scene, pose, row, col);
      if (!std::isfinite(range)) continue;
      ScanPoint point = cell_point(sensor, row, col, range);
      point.time = static_cast<float>(fraction * sensor.scan_period);
      scan.points.push_back(point);
      world_hits.push_back(pose * Eigen::Vector3d(point.x, point.y, point.z));
    }
  }
  return scan;
}

}  // namespace adaptive_lego_loam::test
