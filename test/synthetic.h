#pragma once
// Constructed scans for tests: one ray per range-image cell, cast against a few boxes and an
// optional ground plane, so that the expected clusters and ground are known exactly.

#include <Eigen/Core>
#include <vector>

#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/scan.h"

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

// A point on the beam of (row, col) at `range`, with ring = row.
ScanPoint cell_point(const SensorParams& sensor, int row, int col, double range);

}  // namespace adaptive_lego_loam::test
