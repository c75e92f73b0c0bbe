#pragma once
// Shapes of the objects a scene is made of. Each adds primitives to a GeometrySet with the
// surfaces it is given; placing them is the scene generator's job.

#include <Eigen/Geometry>

#include "adaptive_lego_loam/sim/geometry.h"
#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {

struct CarShape {
  float length = 4.5f, width = 1.8f, height = 1.45f;
  float hood_length = 0.9f, windshield_length = 0.7f, trunk_length = 0.9f;
};

// A sedan, a hatchback or a van (variant 0, 1, 2), a little varied by `rng`.
CarShape random_car_shape(int variant, Rng& rng);

// A car standing on `pose` (x forward): body profile extruded over its width, four wheels.
void add_car(GeometrySet& set, const Eigen::Isometry3f& pose, const CarShape& shape,
             uint32_t body_surface, uint32_t wheel_surface);

// A standing or walking person at `pose` (x forward, feet at z = 0). `swing` in [-1, 1] is the
// phase of the stride: legs and arms swing by up to 20 deg.
void add_person(GeometrySet& set, const Eigen::Isometry3f& pose, float height, float swing,
                uint32_t surface);

// A building block of `size` on `pose`, with a recessed top storey when `setback` > 0.
void add_building(GeometrySet& set, const Eigen::Isometry3f& pose, const Eigen::Vector3f& size,
                  float setback, uint32_t surface);

// A street light at `base`: a pole, an arm reaching `arm` m along `toward`, a lamp head.
void add_street_light(GeometrySet& set, const Eigen::Vector3f& base, const Eigen::Vector3f& toward,
                      float height, float arm, uint32_t surface);

// A traffic sign: a thin pole with a plate facing along `facing`.
void add_sign(GeometrySet& set, const Eigen::Vector3f& base, const Eigen::Vector3f& facing,
              uint32_t pole_surface, uint32_t sign_surface);

// A wooden power pole with a cross arm.
void add_power_pole(GeometrySet& set, const Eigen::Vector3f& base, const Eigen::Vector3f& across,
                    uint32_t surface);

// A fence panel along the x axis of `pose`: posts every 2.5 m and a board face.
void add_fence(GeometrySet& set, const Eigen::Isometry3f& pose, float length, float height,
               uint32_t surface);

}  // namespace adaptive_lego_loam::sim
