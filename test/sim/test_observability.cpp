// The true observability of simulated scans: what the scene's surfaces fix of the sensor's pose,
// in the sensor frame at the scan's time, without the points of moving objects.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>

#include "adaptive_lego_loam/sim/observability.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_sensors.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

namespace {

constexpr double kSigma = 0.02;

// A wall parallel to the x-z plane at `y`, from x = -length/2 to length/2, z from -2 to 20.
void add_wall_along_x(World& world, double y, double length, uint32_t surface) {
  const float half = static_cast<float>(0.5 * length), wy = static_cast<float>(y);
  for (float x = -half; x < half; x += 50.0f) {
    world.tile_at(Eigen::Vector3f(x, wy, 0.0f))
        .add_quad({x, wy, -2.0f}, {x + 50.0f, wy, -2.0f}, {x + 50.0f, wy, 20.0f}, {x, wy, 20.0f},
                  surface);
  }
}

void add_floor(World& world, double half_x, double half_y, double z, uint32_t surface) {
  const float hy = static_cast<float>(half_y), h = static_cast<float>(z);
  for (float x = static_cast<float>(-half_x); x < half_x; x += 50.0f) {
    world.tile_at(Eigen::Vector3f(x, 0.0f, h))
        .add_quad({x, -hy, h}, {x + 50.0f, -hy, h}, {x + 50.0f, hy, h}, {x, hy, h}, surface);
  }
}

// Two walls 3 m either side of the sensor along x, far longer than its range, and a floor.
std::shared_ptr<World> walls_and_floor() {
  auto world = std::make_shared<World>();
  const uint32_t wall = world->add_surface(SemanticClass::kOtherStructure, 0, 0.5f);
  const uint32_t floor = world->add_surface(SemanticClass::kRoad, 0, 0.2f);
  add_wall_along_x(*world, -3.0, 600.0, wall);
  add_wall_along_x(*world, 3.0, 600.0, wall);
  add_floor(*world, 300.0, 3.0, -1.7, floor);
  return world;
}

}  // namespace

TEST(SimObservability, BetweenParallelWallsNothingFixesTheMotionAlongThem) {
  const SimFrame frame = render_one(vlp16(), exact_options(1800), walls_and_floor());
  ASSERT_GT(frame.exact_points.size(), 10000u);
  const Information6 information = scan_information(frame, kSigma);
  // Translation along x (index 3): no surface faces along it.
  EXPECT_LT(information.col(3).norm(), 1e-9 * information.norm());
  // Across the walls, up, and every rotation: plenty.
  const Eigen::SelfAdjointEigenSolver<Information6> solver(information);
  EXPECT_LT(solver.eigenvalues()(0), 1e-9 * solver.eigenvalues()(5));
  EXPECT_GT(solver.eigenvalues()(1), 1e-6 * solver.eigenvalues()(5));
  EXPECT_GT(information(4, 4), 1e6);  // y
  EXPECT_GT(information(5, 5), 1e6);  // z
  const WeakestTranslation weakest = weakest_translation(information);
  EXPECT_TRUE(std::isinf(weakest.sigma_m));
  EXPECT_GT(std::abs(weakest.direction.x()), 0.999);
}

TEST(SimObservability, ABoxRoomFixesEverything) {
  auto world = std::make_shared<World>();
  const uint32_t wall = world->add_surface(SemanticClass::kBuilding, 1, 0.5f);
  // A 10 x 8 x 3 m room, the sensor 1 m above its floor, off its centre.
  const Eigen::Vector3f centre(1.0f, -0.5f, 0.5f);
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      const Eigen::Vector3f half(5.0f, 4.0f, 1.5f);
      Eigen::Vector3f normal = Eigen::Vector3f::Zero();
      normal[axis] = sign;
      add_square(world->tile_at(centre), centre + sign * half[axis] * Eigen::Vector3f::Unit(axis),
                 normal, 6.0f, wall);
    }
  }
  const SimFrame frame = render_one(vlp16(), exact_options(1800), world);
  const Information6 information = scan_information(frame, kSigma);
  const Eigen::SelfAdjointEigenSolver<Information6> solver(information);
  EXPECT_GT(solver.eigenvalues()(0), 1e-6 * solver.eigenvalues()(5));
  const WeakestTranslation weakest = weakest_translation(information);
  EXPECT_LT(weakest.sigma_m, 1e-3);  // tens of thousands of points, 2 cm each
  EXPECT_GT(weakest.sigma_m, 0.0);
}

TEST(SimObservability, ExactPointsLieOnTheirSurfacesInTheFrameAtTheScansTime) {
  // A wall 10 m ahead; the sensor drives along it sideways at 10 m/s and yaws at 30 deg/s during
  // a skewed sweep: each column fires from elsewhere, yet every exact point, put in the world by
  // the pose at the scan's time, lies on the wall.
  auto world = std::make_shared<World>();
  const uint32_t wall = world->add_surface(SemanticClass::kBuilding, 1, 0.5f);
  add_square(world->tile_at(Eigen::Vector3f(10, 0, 0)), Eigen::Vector3f(10, 0, 0),
             Eigen::Vector3f(-1, 0, 0), 60.0f, wall);
  std::vector<double> times;
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < 4; ++k) {
    times.push_back(0.1 * k);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(0.0, 1.0 * k, 0.0);
    pose.linear() = Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    poses.push_back(pose);
  }
  SimSensorOptions options = exact_options(1800);
  options.motion_distortion = true;
  options.range_noise_m = 0.05;  // the scan is noisy, its exact points are not
  const SimFrame frame = render_one(vlp16(), options, world,
                                    std::make_shared<SampledTrajectory>(times, poses, Shake()), 2);
  ASSERT_GT(frame.exact_points.size(), 1000u);
  double worst = 0.0, noisy = 0.0;
  for (std::size_t i = 0; i < frame.exact_points.size(); ++i) {
    const Eigen::Vector3d world_point = frame.sensor_pose * frame.exact_points[i].cast<double>();
    worst = std::max(worst, std::abs(world_point.x() - 10.0));
    const Eigen::Vector3d normal =
        frame.sensor_pose.linear() * frame.exact_normals[i].cast<double>();
    EXPECT_NEAR(std::abs(normal.x()), 1.0, 1e-5);
    const ScanPoint& p = frame.scan.points[i];
    noisy =
        std::max(noisy, double((Eigen::Vector3f(p.x, p.y, p.z) - frame.exact_points[i]).norm()));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(noisy, 0.1);  // the raw points are skewed and noisy
}

TEST(SimObservability, MovingObjectsAreLeftOutTheGroundCounts) {
  SimFrame frame;
  // A floor point and a point on a passing car's side.
  frame.exact_points = {{5.0f, 0.0f, -1.7f}, {0.0f, 3.0f, 0.0f}};
  frame.exact_normals = {{0.0f, 0.0f, 1.0f}, {0.0f, -1.0f, 0.0f}};
  frame.labels = {pack_label(SemanticClass::kRoad, 0), pack_label(SemanticClass::kMovingCar, 7)};
  const Information6 information = scan_information(frame, 0.1);
  const Information6 floor_only =
      point_to_plane_information({frame.exact_points[0]}, {frame.exact_normals[0]}, 0.1);
  EXPECT_TRUE(information.isApprox(floor_only));
  EXPECT_NEAR(information(5, 5), 1.0 / 0.01, 1e-9);  // the floor's normal is z
  EXPECT_NEAR(information(4, 4), 0.0, 1e-12);        // the car's would have been y
  // J = [p x n, n]: the floor point 5 m ahead constrains pitch, -5 per radian of it.
  EXPECT_NEAR(information(1, 1), 25.0 / 0.01, 1e-6);
  EXPECT_NEAR(information(1, 5), -5.0 / 0.01, 1e-9);
}

TEST(SimObservability, TheCsvSaysWhatItHoldsAndHasALinePerScan) {
  const std::string header = observability_header(0.02);
  EXPECT_NE(header.find("sigma: 0.02 m"), std::string::npos);
  EXPECT_NE(header.find("rotation about x, y, z (rad), then translation along x, y, z (m)"),
            std::string::npos);
  for (std::size_t start = 0; start < header.size(); start = header.find('\n', start) + 1)
    EXPECT_EQ(header[start], '#');
  EXPECT_NE(observability_header(0.0).find("sigma: 1 m"), std::string::npos);
  EXPECT_DOUBLE_EQ(observability_sigma(0.0), 1.0);
  Information6 information = Information6::Identity();
  information(0, 5) = information(5, 0) = -2.5;
  const std::string line = observability_line(7, information);
  EXPECT_EQ(line.rfind("7,1.000000000e+00,0.000000000e+00,", 0), 0u) << line;
  EXPECT_EQ(std::count(line.begin(), line.end(), ','), 36);
  EXPECT_NE(line.find(",-2.500000000e+00,"), std::string::npos);
  EXPECT_EQ(line.back(), '\n');
}
