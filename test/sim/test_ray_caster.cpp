// The simulator's sensor model against analytic answers: ranges to a plane, a box and a cylinder,
// ring and time fields, motion distortion, noise, dropouts, intensity and labels.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_sensors.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

namespace {

struct Index {
  int ring, column;
};

// The cell a point came from: ring from the field, column from its firing time.
Index cell_of(const ScanPoint& point, const LidarModel& model) {
  const double column = point.time / model.sensor().scan_period * model.columns();
  return {point.ring, static_cast<int>(std::lround(column))};
}

double plane_range(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                   const Eigen::Vector3d& on_plane, const Eigen::Vector3d& normal) {
  const double along = normal.dot(direction);
  if (std::abs(along) < 1e-12) return kInf;
  const double t = normal.dot(on_plane - origin) / along;
  return t > 0 ? t : kInf;
}

double box_range(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                 const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  double near = 0.0, far = kInf;
  for (int axis = 0; axis < 3; ++axis) {
    double t0 = (low[axis] - origin[axis]) / direction[axis];
    double t1 = (high[axis] - origin[axis]) / direction[axis];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return near <= far && near > 0 ? near : kInf;
}

// Side of a vertical cylinder (axis through `centre`, from z0 to z1).
double cylinder_range(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      const Eigen::Vector2d& centre, double radius, double z0, double z1) {
  const Eigen::Vector2d o = origin.head<2>() - centre, d = direction.head<2>();
  const double a = d.squaredNorm(), b = 2 * o.dot(d), c = o.squaredNorm() - radius * radius;
  const double discriminant = b * b - 4 * a * c;
  if (discriminant < 0) return kInf;
  const double t = (-b - std::sqrt(discriminant)) / (2 * a);
  const double z = origin.z() + t * direction.z();
  return t > 0 && z >= z0 && z <= z1 ? t : kInf;
}

}  // namespace

TEST(SimRayCasting, PlaneAtKnownDistanceAndAngle) {
  auto world = std::make_shared<World>();
  const uint32_t wall = world->add_surface(SemanticClass::kBuilding, 3, 0.5f);
  // A wall 10 m ahead, turned 30 deg about z.
  const Eigen::Vector3d normal(std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0), on_wall(10, 0, 0);
  add_square(world->tile_at(Eigen::Vector3f(10, 0, 0)), on_wall.cast<float>(), normal.cast<float>(),
             60.0f, wall);
  const SensorParams sensor = vlp16();
  const LidarModel model(sensor, exact_options(1800));
  const SimFrame frame = render_one(sensor, exact_options(1800), world);

  const auto [axis_u, axis_v] = square_axes(normal.cast<float>());
  int expected = 0;
  for (int ring = 0; ring < model.beams(); ++ring) {
    for (int column = 0; column < model.columns(); ++column) {
      const Eigen::Vector3d d = model.direction(ring, column);
      const double range = plane_range(Eigen::Vector3d::Zero(), d, on_wall, normal);
      if (range > sensor.max_range) continue;
      const Eigen::Vector3d offset = range * d - on_wall;
      if (std::abs(offset.dot(axis_u.cast<double>())) <= 60.0 &&
          std::abs(offset.dot(axis_v.cast<double>())) <= 60.0 &&
          std::abs(normal.dot(d)) > std::cos(89.9 * M_PI / 180))
        ++expected;
    }
  }
  ASSERT_GT(expected, 1000);
  EXPECT_NEAR(static_cast<double>(frame.scan.points.size()), expected, 3);
  for (std::size_t i = 0; i < frame.scan.points.size(); ++i) {
    const ScanPoint& p = frame.scan.points[i];
    const Index cell = cell_of(p, model);
    const Eigen::Vector3d d = model.direction(cell.ring, cell.column);
    const double range = plane_range(Eigen::Vector3d::Zero(), d, on_wall, normal);
    ASSERT_NEAR((Eigen::Vector3d(p.x, p.y, p.z) - range * d).norm(), 0.0, 2e-3) << "point " << i;
    ASSERT_EQ(frame.labels[i], pack_label(SemanticClass::kBuilding, 3));
    ASSERT_NEAR(frame.normals[i].cast<double>().dot(-normal), 1.0, 1e-5);
    // Lambertian intensity from the surface's reflectivity.
    ASSERT_NEAR(p.intensity, 0.5 * std::abs(normal.dot(d)), 1e-4);
  }
}

TEST(SimRayCasting, BoxOnGroundWithLabels) {
  auto world = std::make_shared<World>();
  const uint32_t ground = world->add_surface(SemanticClass::kRoad, 0, 0.2f);
  const uint32_t box = world->add_surface(SemanticClass::kCar, 9, 0.6f);
  const double ground_z = -1.73;
  add_square(world->tile_at(Eigen::Vector3f::Zero()), Eigen::Vector3f(0, 0, ground_z),
             Eigen::Vector3f::UnitZ(), 80.0f, ground);
  const Eigen::Vector3d low(4, -3, ground_z), high(7, -1, 0.2);
  Eigen::Isometry3f bottom = Eigen::Isometry3f::Identity();
  bottom.translate(Eigen::Vector3f(5.5f, -2.0f, ground_z));
  add_box(world->tile_at(Eigen::Vector3f(5.5f, -2.0f, 0)), bottom, (high - low).cast<float>(), box);
  const SensorParams sensor = vlp16();
  const SimSensorOptions options = exact_options(1800);
  const LidarModel model(sensor, options);
  const SimFrame frame = render_one(sensor, options, world);

  int on_box = 0, on_ground = 0;
  for (std::size_t i = 0; i < frame.scan.points.size(); ++i) {
    const ScanPoint& p = frame.scan.points[i];
    const Index cell = cell_of(p, model);
    const Eigen::Vector3d d = model.direction(cell.ring, cell.column);
    const double to_box = box_range(Eigen::Vector3d::Zero(), d, low, high);
    const double to_ground = plane_range(Eigen::Vector3d::Zero(), d,
                                         Eigen::Vector3d(0, 0, ground_z), Eigen::Vector3d::UnitZ());
    const double range = std::min(to_box, to_ground);
    ASSERT_LT(range, kInf) << "a return where the analytic ray hits nothing";
    ASSERT_NEAR((Eigen::Vector3d(p.x, p.y, p.z) - range * d).norm(), 0.0, 2e-3);
    if (to_box < to_ground - 1e-3) {
      ++on_box;
      ASSERT_EQ(frame.labels[i], pack_label(SemanticClass::kCar, 9));
    } else if (to_ground < to_box - 1e-3) {
      ++on_ground;
      ASSERT_EQ(label_class(frame.labels[i]), SemanticClass::kRoad);
    }
  }
  int expected_on_box = 0;
  for (int ring = 0; ring < model.beams(); ++ring) {
    for (int column = 0; column < model.columns(); ++column) {
      const Eigen::Vector3d d = model.direction(ring, column);
      if (box_range(Eigen::Vector3d::Zero(), d, low, high) < kInf) ++expected_on_box;
    }
  }
  EXPECT_GT(on_box, 500);
  EXPECT_NEAR(on_box, expected_on_box, 2);
  EXPECT_GT(on_ground, 5000);
}

TEST(SimRayCasting, CylinderAndBeamOrigins) {
  // KITTI's HDL-64E: rays of beam k start at (0, 0, offset_k).
  auto world = std::make_shared<World>();
  const uint32_t pole = world->add_surface(SemanticClass::kPole, 4, 0.5f);
  const Eigen::Vector2d centre(6.0, 3.0);
  const double radius = 0.5, z0 = -3.0, z1 = 4.0;
  world->tile_at(Eigen::Vector3f(6, 3, 0))
      .add_cylinder(Eigen::Vector3f(6, 3, z0), Eigen::Vector3f(6, 3, z1), radius, pole);
  const SensorParams sensor = kitti_hdl64e();
  const LidarModel model(sensor, exact_options(2083));
  const SimFrame frame = render_one(sensor, exact_options(2083), world);

  int expected = 0;
  for (int ring = 0; ring < model.beams(); ++ring) {
    for (int column = 0; column < model.columns(); ++column) {
      if (cylinder_range(model.beam_origin(ring), model.direction(ring, column), centre, radius, z0,
                         z1) < kInf)
        ++expected;
    }
  }
  ASSERT_GT(expected, 1000);
  EXPECT_NEAR(static_cast<double>(frame.scan.points.size()), expected, expected * 0.01);
  for (std::size_t i = 0; i < frame.scan.points.size(); ++i) {
    const ScanPoint& p = frame.scan.points[i];
    const Index cell = cell_of(p, model);
    const Eigen::Vector3d origin = model.beam_origin(cell.ring),
                          d = model.direction(cell.ring, cell.column);
    const double range = cylinder_range(origin, d, centre, radius, z0, z1);
    ASSERT_LT(range, kInf);
    ASSERT_NEAR((Eigen::Vector3d(p.x, p.y, p.z) - (origin + range * d)).norm(), 0.0, 2e-3);
    ASSERT_EQ(frame.labels[i], pack_label(SemanticClass::kPole, 4));
  }
}

TEST(SimRayCasting, RingAndTimeFollowTheFiringOrder) {
  auto world = std::make_shared<World>();
  const uint32_t ground = world->add_surface(SemanticClass::kRoad, 0, 0.2f);
  add_square(world->tile_at(Eigen::Vector3f::Zero()), Eigen::Vector3f(0, 0, -1.73f),
             Eigen::Vector3f::UnitZ(), 80.0f, ground);
  const SensorParams sensor = vlp16();
  const LidarModel model(sensor, exact_options(1800));
  const SimFrame frame = render_one(sensor, exact_options(1800), world);
  ASSERT_GT(frame.scan.points.size(), 1000u);
  EXPECT_TRUE(frame.scan.has_ring);
  EXPECT_TRUE(frame.scan.has_time);
  float previous_time = 0.0f;
  for (const ScanPoint& p : frame.scan.points) {
    // Elevation of the ring's beam, azimuth turning clockwise from behind as time goes on.
    const double elevation = std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / M_PI;
    ASSERT_NEAR(elevation, sensor.beam_angles_deg[p.ring], 1e-3);
    const double azimuth = M_PI - 2.0 * M_PI * p.time / sensor.scan_period;
    ASSERT_NEAR(std::remainder(std::atan2(p.y, p.x) - azimuth, 2 * M_PI), 0.0, 1e-4);
    ASSERT_GE(p.time, previous_time);
    ASSERT_LT(p.time, sensor.scan_period);
    previous_time = p.time;
  }
}

TEST(SimRayCasting, MotionDistortionMovesPointsWithTheirFiringTime) {
  auto world = std::make_shared<World>();
  const uint32_t wall = world->add_surface(SemanticClass::kBuilding, 1, 0.5f);
  add_square(world->tile_at(Eigen::Vector3f(20, 0, 0)), Eigen::Vector3f(20, 0, 0),
             -Eigen::Vector3f::UnitX(), 40.0f, wall);
  // Driving along x at 10 m/s; frame 1 at 0.5 s, 5 m on.
  std::vector<Eigen::Isometry3d> poses(3, Eigen::Isometry3d::Identity());
  poses[1].translation().x() = 5.0;
  poses[2].translation().x() = 10.0;
  auto driving =
      std::make_shared<SampledTrajectory>(std::vector<double>{0.0, 0.5, 1.0}, poses, Shake());
  const SensorParams sensor = vlp16();
  SimSensorOptions options = exact_options(1800);
  options.motion_distortion = true;
  const SimFrame skewed = render_one(sensor, options, world, driving, 1);
  options.motion_distortion = false;
  const SimFrame deskewed = render_one(sensor, options, world, driving, 1);
  ASSERT_GT(skewed.scan.points.size(), 500u);
  ASSERT_GT(deskewed.scan.points.size(), 500u);
  // The sweep ends at the frame's time and pose (as a Velodyne driver stamps a scan with its
  // last packet); each point's time runs from the sweep's first firing.
  EXPECT_NEAR(skewed.sensor_pose.translation().x(), 5.0, 1e-9);
  EXPECT_NEAR(skewed.scan.stamp, 0.5, 1e-9);
  for (const ScanPoint& p : skewed.scan.points)
    ASSERT_NEAR(p.x, 20.0 - 10.0 * (0.5 - sensor.scan_period + p.time), 2e-3);
  for (const ScanPoint& p : deskewed.scan.points)
    ASSERT_NEAR(p.x, 15.0, 2e-3);
}
