#pragma once
// Constructed scenes of boxes on flat ground, and an HDL-64E-like sensor to see them with.

#include <utility>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "support/synthetic.h"

namespace adaptive_lego_loam::test {

// HDL-64E-like layout, evenly spaced, ground possible in rows up to -3.5 deg.
inline Config synthetic_config() {
  Config config;
  config.sensor = test::even_sensor(64, 1800, -24.9, 2.0);
  config.sensor.ground_rows = 50;
  config.sensor.max_range = 100.0;
  return config;
}

inline Scene with_ground(std::vector<Box> boxes) {
  Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.73;
  scene.boxes = std::move(boxes);
  return scene;
}

inline Scene corridor() {
  return with_ground({{{-60, 2.8, -1.73}, {60, 3.0, 3.0}}, {{-60, -3.0, -1.73}, {60, -2.8, 3.0}}});
}

// A road between rows of guard-rail posts every 2 m, 6 m to either side, from -half_length to
// half_length along x: the same picture every 2 m.
inline Scene post_rows(double half_length) {
  Scene scene;
  scene.has_ground = true;
  for (double x = -half_length; x <= half_length; x += 2.0) {
    for (double y : {-6.0, 6.0})
      scene.boxes.push_back({{x, y, -2.0}, {x + 0.15, y + 0.15, -0.9}});
  }
  return scene;
}

// A square room, 12 m a side.
inline Scene box_room() {
  return with_ground({{{5.8, -6, -1.73}, {6.0, 6, 3}},
                      {{-6.0, -6, -1.73}, {-5.8, 6, 3}},
                      {{-6, 5.8, -1.73}, {6, 6.0, 3}},
                      {{-6, -6.0, -1.73}, {6, -5.8, 3}}});
}

// Four blocks of buildings at the corners of two crossing 8 m wide streets.
inline Scene crossroads() {
  std::vector<Box> blocks;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const Eigen::Vector3d a(sx * 4, sy * 4, -1.73), b(sx * 40, sy * 40, 8.0);
      blocks.push_back({a.cwiseMin(b), a.cwiseMax(b)});
    }
  }
  return with_ground(blocks);
}

}  // namespace adaptive_lego_loam::test
