#include "adaptive_lego_loam/sim/objects.h"

#include <cmath>
#include <vector>

namespace adaptive_lego_loam::sim {
namespace {

constexpr float kPi = static_cast<float>(M_PI);

}  // namespace

CarShape random_car_shape(int variant, Rng& rng) {
  CarShape shape;
  const float jitter = static_cast<float>(rng.uniform(0.95, 1.05));
  switch (variant % 3) {
    case 0:  // sedan
      shape = {4.6f, 1.8f, 1.45f, 1.0f, 0.8f, 0.9f};
      break;
    case 1:  // hatchback
      shape = {4.0f, 1.75f, 1.5f, 0.8f, 0.8f, 0.25f};
      break;
    default:  // van
      shape = {5.0f, 2.0f, 2.1f, 0.6f, 0.5f, 0.05f};
      break;
  }
  shape.length *= jitter;
  shape.width *= jitter;
  shape.height *= static_cast<float>(rng.uniform(0.95, 1.05));
  return shape;
}

void add_car(GeometrySet& set, const Eigen::Isometry3f& pose, const CarShape& c,
             uint32_t body_surface, uint32_t wheel_surface) {
  const float half = 0.5f * c.length, clearance = 0.25f, belt = 0.55f * c.height;
  // Side profile, star-shaped from its first vertex (so the fan triangulation holds).
  const std::vector<Eigen::Vector2f> profile = {
      {-half, clearance},
      {half, clearance},
      {half, belt - 0.1f},
      {half - c.hood_length, belt + 0.05f},
      {half - c.hood_length - c.windshield_length, c.height},
      {-half + c.trunk_length + 0.4f, c.height},
      {-half + c.trunk_length, belt + 0.05f},
      {-half, belt}};
  add_extruded_profile(set, pose, profile, c.width, body_surface);
  const float radius = 0.32f, axle = half - 0.85f;
  for (float x : {-axle, axle}) {
    for (float side : {-1.0f, 1.0f}) {
      const float outer = side * 0.5f * c.width, inner = side * (0.5f * c.width - 0.22f);
      set.add_prism(pose * Eigen::Vector3f(x, inner, radius),
                    pose * Eigen::Vector3f(x, outer, radius), radius, 16, wheel_surface);
    }
  }
}

void add_person(GeometrySet& set, const Eigen::Isometry3f& pose, float height, float swing,
                uint32_t surface) {
  const float h = height, girth = h / 1.75f;
  const float hip = 0.53f * h, shoulder = 0.82f * h, arm = 0.33f * h;
  const float angle = 20.0f * kPi / 180.0f * swing;
  for (float side : {-1.0f, 1.0f}) {
    const float leg_angle = side * angle;
    const Eigen::Vector3f hip_joint(0.0f, side * 0.1f * girth, hip);
    const Eigen::Vector3f foot =
        hip_joint +
        (hip - 0.02f) * Eigen::Vector3f(std::sin(leg_angle), 0.0f, -std::cos(leg_angle));
    set.add_prism(pose * hip_joint, pose * foot, 0.07f * girth, 8, surface);
    const Eigen::Vector3f shoulder_joint(0.0f, side * 0.21f * girth, shoulder);
    const Eigen::Vector3f hand =
        shoulder_joint + arm * Eigen::Vector3f(-std::sin(leg_angle), 0.0f, -std::cos(leg_angle));
    set.add_prism(pose * shoulder_joint, pose * hand, 0.045f * girth, 8, surface);
  }
  set.add_prism(pose * Eigen::Vector3f(0.0f, 0.0f, hip - 0.05f),
                pose * Eigen::Vector3f(0.0f, 0.0f, shoulder + 0.03f), 0.16f * girth, 12, surface);
  set.add_prism(pose * Eigen::Vector3f(0.0f, 0.0f, shoulder + 0.06f),
                pose * Eigen::Vector3f(0.0f, 0.0f, h), 0.1f * girth, 12, surface);
}

void add_building(GeometrySet& set, const Eigen::Isometry3f& pose, const Eigen::Vector3f& size,
                  float setback, uint32_t surface) {
  if (setback <= 0.0f || size.z() < 9.0f) {
    add_box(set, pose, size, surface);
    return;
  }
  const float lower = size.z() - 3.0f;
  add_box(set, pose, Eigen::Vector3f(size.x(), size.y(), lower), surface);
  Eigen::Isometry3f top = pose;
  top.translate(Eigen::Vector3f(0.0f, 0.0f, lower));
  add_box(set, top, Eigen::Vector3f(size.x() - 2 * setback, size.y() - 2 * setback, 3.0f), surface);
}

void add_street_light(GeometrySet& set, const Eigen::Vector3f& base, const Eigen::Vector3f& toward,
                      float height, float arm, uint32_t surface) {
  const Eigen::Vector3f top = base + Eigen::Vector3f(0.0f, 0.0f, height);
  const Eigen::Vector3f reach = top + arm * toward.normalized();
  set.add_prism(base - Eigen::Vector3f(0, 0, 0.3f), top, 0.09f, 12, surface);
  set.add_prism(top - Eigen::Vector3f(0, 0, 0.1f), reach, 0.05f, 8, surface);
  add_box(set, yaw_pose(reach - Eigen::Vector3f(0, 0, 0.2f), std::atan2(toward.y(), toward.x())),
          Eigen::Vector3f(0.6f, 0.3f, 0.2f), surface);
}

void add_sign(GeometrySet& set, const Eigen::Vector3f& base, const Eigen::Vector3f& facing,
              uint32_t pole_surface, uint32_t sign_surface) {
  set.add_prism(base - Eigen::Vector3f(0, 0, 0.3f), base + Eigen::Vector3f(0, 0, 2.6f), 0.035f, 8,
                pole_surface);
  const float yaw = std::atan2(facing.y(), facing.x());
  add_box(set, yaw_pose(base + Eigen::Vector3f(0, 0, 2.0f) + 0.05f * facing.normalized(), yaw),
          Eigen::Vector3f(0.04f, 0.65f, 0.65f), sign_surface);
}

void add_power_pole(GeometrySet& set, const Eigen::Vector3f& base, const Eigen::Vector3f& across,
                    uint32_t surface) {
  const Eigen::Vector3f top = base + Eigen::Vector3f(0, 0, 9.0f);
  set.add_prism(base - Eigen::Vector3f(0, 0, 0.5f), top, 0.14f, 12, surface);
  const Eigen::Vector3f arm = 1.2f * across.normalized();
  const Eigen::Vector3f arm_height = top - Eigen::Vector3f(0, 0, 0.6f);
  set.add_prism(arm_height - arm, arm_height + arm, 0.06f, 8, surface);
}

void add_fence(GeometrySet& set, const Eigen::Isometry3f& pose, float length, float height,
               uint32_t surface) {
  Eigen::Isometry3f panel = pose;
  panel.translate(Eigen::Vector3f(0.5f * length, 0.0f, -0.2f));
  add_box(set, panel, Eigen::Vector3f(length, 0.04f, height + 0.2f), surface);
  const int posts = std::max(2, static_cast<int>(std::ceil(length / 2.5f)) + 1);
  for (int i = 0; i < posts; ++i) {
    const float x = length * i / (posts - 1);
    Eigen::Isometry3f post = pose;
    post.translate(Eigen::Vector3f(x, 0.06f, -0.3f));
    add_box(set, post, Eigen::Vector3f(0.1f, 0.08f, height + 0.4f), surface);
  }
}

}  // namespace adaptive_lego_loam::sim
