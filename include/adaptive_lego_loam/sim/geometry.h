#pragma once
// Plain geometry the simulator's scenes are made of: triangles and capped cylinders, each
// primitive pointing at a surface (semantic class, instance, reflectivity). No Embree here.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/sim/labels.h"

namespace adaptive_lego_loam::sim {

struct Surface {
  SemanticClass semantic = SemanticClass::kUnlabeled;
  // 0 for prototypes shared by several objects: the object's instance id is used then.
  uint16_t instance = 0;
  float reflectivity = 0.5f;  // diffuse reflectivity in [0, 1]
};

// A capped cylinder from a to b (poles, trunks, limbs).
struct Cylinder {
  Eigen::Vector3f a, b;
  float radius = 0.1f;
  uint32_t surface = 0;
};

struct GeometrySet {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint32_t> triangle_surfaces;  // one per triangle
  std::vector<Cylinder> cylinders;

  bool empty() const { return triangles.empty() && cylinders.empty(); }
  uint32_t add_vertex(const Eigen::Vector3f& vertex);
  void add_triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                    uint32_t surface);
  // Corners in order around the quad.
  void add_quad(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                const Eigen::Vector3f& d, uint32_t surface);
  void add_cylinder(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                    uint32_t surface);
  // A capped cylinder as a prism of `sides` triangle pairs: cheaper to trace than a cylinder
  // when the set is mostly triangles (trunks and limbs among leaves).
  void add_prism(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius, int sides,
                 uint32_t surface);
  Eigen::AlignedBox3f bounds() const;
};

// A box of `size` (x, y, z) whose bottom face is centred on `pose`'s origin.
void add_box(GeometrySet& set, const Eigen::Isometry3f& pose, const Eigen::Vector3f& size,
             uint32_t surface);

// A convex polygon in the local x-z plane (counter-clockwise seen from +y), extruded over
// `width` along y, centred on y = 0: the side profile of a car.
void add_extruded_profile(GeometrySet& set, const Eigen::Isometry3f& pose,
                          const std::vector<Eigen::Vector2f>& profile_xz, float width,
                          uint32_t surface);

// Pose with the given position and a rotation of `yaw` about z.
Eigen::Isometry3f yaw_pose(const Eigen::Vector3f& position, float yaw);

}  // namespace adaptive_lego_loam::sim
