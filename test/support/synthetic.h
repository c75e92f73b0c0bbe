#pragma once
// Constructed scans for tests: one ray per range-image cell, cast against a few boxes and an
// optional ground plane, so that the expected clusters and ground are known exactly.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam::test {

struct Box {
  Eigen::Vector3d min, max;
};

struct Scene {
  std::vector<Box> boxes;
  bool has_ground = false;
  double ground_z = -1.73;
};

// A sensor with evenly spaced beams, rows from the ring field.
SensorParams even_sensor(int rows, int cols, double vertical_min_deg, double vertical_max_deg);

// The direction of the beam through the centre of a cell.
Eigen::Vector3d beam_direction(const SensorParams& sensor, int row, int col);

// One point per cell whose ray hits the scene, with ring = row.
Scan render(const SensorParams& sensor, const Scene& scene);

// The same seen by a sensor at `sensor_pose` in the scene's frame; points in the sensor frame.
Scan render(const SensorParams& sensor, const Scene& scene, const Eigen::Isometry3d& sensor_pose);

// A sweep during which the sensor moves from `start` by `sweep_motion` (the pose at the sweep's
// end in the frame of its start, followed as interpolate_motion does). The head turns clockwise:
// column c fires at the sweep fraction (cols - 1 - c) / cols, and the points come in firing order.
// Each point is in the frame the sensor had when it fired, its time field set; `world_hits`
// receives each point's position in the scene's frame.
Scan render_sweep(const SensorParams& sensor, const Scene& scene, const Eigen::Isometry3d& start,
                  const Eigen::Isometry3d& sweep_motion, std::vector<Eigen::Vector3d>& world_hits);

// The same with the sensor at pose_at(fraction) (start and end: 0 and 1) in the scene's frame.
Scan render_sweep(const SensorParams& sensor, const Scene& scene,
                  const std::function<Eigen::Isometry3d(double)>& pose_at,
                  std::vector<Eigen::Vector3d>& world_hits);

// A point on the beam of (row, col) at `range`, with ring = row.
ScanPoint cell_point(const SensorParams& sensor, int row, int col, double range);

// Scatter such as a bush's leaves: a point on every beam of rows [row_begin, row_end) and columns
// [col_begin, col_end) (wrapped into the image), at range_m plus a uniform random depth below
// depth_m, appended to `scan` in row-major order.
void add_scatter(const SensorParams& sensor, int row_begin, int row_end, int col_begin, int col_end,
                 double range_m, double depth_m, std::mt19937& rng, Scan& scan);

}  // namespace adaptive_lego_loam::test
