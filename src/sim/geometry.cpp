#include "adaptive_lego_loam/sim/geometry.h"

#include <cmath>

namespace adaptive_lego_loam::sim {

uint32_t GeometrySet::add_vertex(const Eigen::Vector3f& vertex) {
  vertices.push_back(vertex);
  return static_cast<uint32_t>(vertices.size() - 1);
}

void GeometrySet::add_triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                               const Eigen::Vector3f& c, uint32_t surface) {
  const uint32_t first = add_vertex(a);
  add_vertex(b);
  add_vertex(c);
  triangles.push_back({first, first + 1, first + 2});
  triangle_surfaces.push_back(surface);
}

void GeometrySet::add_quad(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                           const Eigen::Vector3f& c, const Eigen::Vector3f& d, uint32_t surface) {
  const uint32_t first = add_vertex(a);
  add_vertex(b);
  add_vertex(c);
  add_vertex(d);
  triangles.push_back({first, first + 1, first + 2});
  triangles.push_back({first, first + 2, first + 3});
  triangle_surfaces.insert(triangle_surfaces.end(), 2, surface);
}

void GeometrySet::add_cylinder(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                               uint32_t surface) {
  cylinders.push_back({a, b, radius, surface});
}

void GeometrySet::add_prism(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                            int sides, uint32_t surface) {
  const Eigen::Vector3f axis = (b - a).normalized();
  const Eigen::Vector3f u = axis.unitOrthogonal(), v = axis.cross(u);
  std::vector<Eigen::Vector3f> ring;
  for (int k = 0; k < sides; ++k) {
    const float angle = 2.0f * static_cast<float>(M_PI) * k / sides;
    ring.push_back(radius * (std::cos(angle) * u + std::sin(angle) * v));
  }
  for (int k = 0; k < sides; ++k) {
    const Eigen::Vector3f& p = ring[k];
    const Eigen::Vector3f& q = ring[(k + 1) % sides];
    add_quad(a + p, a + q, b + q, b + p, surface);
  }
  for (int k = 1; k + 1 < sides; ++k) {  // the caps, as fans
    add_triangle(a + ring[0], a + ring[k + 1], a + ring[k], surface);
    add_triangle(b + ring[0], b + ring[k], b + ring[k + 1], surface);
  }
}

Eigen::AlignedBox3f GeometrySet::bounds() const {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& vertex : vertices)
    box.extend(vertex);
  for (const Cylinder& cylinder : cylinders) {
    const Eigen::Vector3f pad = Eigen::Vector3f::Constant(cylinder.radius);
    box.extend(cylinder.a - pad).extend(cylinder.a + pad);
    box.extend(cylinder.b - pad).extend(cylinder.b + pad);
  }
  return box;
}

void add_box(GeometrySet& set, const Eigen::Isometry3f& pose, const Eigen::Vector3f& size,
             uint32_t surface) {
  const float hx = 0.5f * size.x(), hy = 0.5f * size.y(), h = size.z();
  auto corner = [&](float x, float y, float z) -> Eigen::Vector3f {
    return pose * Eigen::Vector3f(x, y, z);
  };
  const Eigen::Vector3f b0 = corner(-hx, -hy, 0), b1 = corner(hx, -hy, 0), b2 = corner(hx, hy, 0),
                        b3 = corner(-hx, hy, 0);
  const Eigen::Vector3f t0 = corner(-hx, -hy, h), t1 = corner(hx, -hy, h), t2 = corner(hx, hy, h),
                        t3 = corner(-hx, hy, h);
  set.add_quad(b0, b3, b2, b1, surface);  // bottom
  set.add_quad(t0, t1, t2, t3, surface);  // top
  set.add_quad(b0, b1, t1, t0, surface);  // -y
  set.add_quad(b1, b2, t2, t1, surface);  // +x
  set.add_quad(b2, b3, t3, t2, surface);  // +y
  set.add_quad(b3, b0, t0, t3, surface);  // -x
}

void add_extruded_profile(GeometrySet& set, const Eigen::Isometry3f& pose,
                          const std::vector<Eigen::Vector2f>& profile_xz, float width,
                          uint32_t surface) {
  const float half = 0.5f * width;
  auto at = [&](const Eigen::Vector2f& p, float y) -> Eigen::Vector3f {
    return pose * Eigen::Vector3f(p.x(), y, p.y());
  };
  const std::size_t n = profile_xz.size();
  for (std::size_t i = 1; i + 1 < n; ++i) {  // the two sides, as fans
    set.add_triangle(at(profile_xz[0], half), at(profile_xz[i], half), at(profile_xz[i + 1], half),
                     surface);
    set.add_triangle(at(profile_xz[0], -half), at(profile_xz[i + 1], -half),
                     at(profile_xz[i], -half), surface);
  }
  for (std::size_t i = 0; i < n; ++i) {  // the rim
    const Eigen::Vector2f& p = profile_xz[i];
    const Eigen::Vector2f& q = profile_xz[(i + 1) % n];
    set.add_quad(at(p, -half), at(q, -half), at(q, half), at(p, half), surface);
  }
}

Eigen::Isometry3f yaw_pose(const Eigen::Vector3f& position, float yaw) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translate(position);
  pose.rotate(Eigen::AngleAxisf(yaw, Eigen::Vector3f::UnitZ()));
  return pose;
}

}  // namespace adaptive_lego_loam::sim
