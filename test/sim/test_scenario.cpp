// Each scenario generates, is deterministic, and has the character it claims; the sequence
// writer's output is what KITTI and SemanticKITTI readers expect.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/sim/observability.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/sequence_writer.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_requests.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

namespace {

struct Character {
  long points = 0, non_ground = 0;
  std::map<SemanticClass, long> per_class;
  long facing_along_road = 0;  // non-ground points whose surface faces along x (the road)
  long structure_left = 0, structure_right = 0;

  double share(SemanticClass semantic) const {
    const auto found = per_class.find(semantic);
    return found == per_class.end() ? 0.0 : double(found->second) / points;
  }
  double vegetation_share() const {
    return share(SemanticClass::kVegetation) + share(SemanticClass::kTrunk);
  }
  double non_ground_share(std::initializer_list<SemanticClass> classes) const {
    long count = 0;
    for (SemanticClass semantic : classes) {
      const auto found = per_class.find(semantic);
      if (found != per_class.end()) count += found->second;
    }
    return double(count) / non_ground;
  }
};

Character character_of(const std::vector<SimFrame>& frames) {
  Character c;
  for (const SimFrame& frame : frames) {
    for (std::size_t i = 0; i < frame.labels.size(); ++i) {
      const SemanticClass semantic = label_class(frame.labels[i]);
      ++c.points;
      ++c.per_class[semantic];
      if (is_ground_class(semantic)) continue;
      ++c.non_ground;
      if (std::abs(frame.normals[i].x()) > 0.7f) ++c.facing_along_road;
      if (semantic == SemanticClass::kOtherStructure) {
        (frame.scan.points[i].y > 0 ? c.structure_left : c.structure_right)++;
      }
    }
  }
  return c;
}

Character character_of(ScenarioKind kind) {
  return character_of(frames_of(kind));
}

// A VLP-16 (1800 columns, raw sweeps) driving `scene`.
LidarSimulator simulator_for(const GeneratedScene& scene, uint64_t seed) {
  SimSensorOptions options;
  options.columns = 1800;
  return LidarSimulator(LidarModel(vlp16(), options), scene.world, scene.trajectory, seed);
}

// The first frame at which the drive has gone `past` m beyond the tunnel's portal.
int frame_inside(const GeneratedScene& scene, double past) {
  const Trajectory& drive = *scene.trajectory;
  double driven = 0.0;
  for (int frame = 1; frame < drive.frame_limit(); ++frame) {
    driven += (drive.sensor_pose(drive.frame_time(frame)).translation() -
               drive.sensor_pose(drive.frame_time(frame - 1)).translation())
                  .norm();
    if (driven >= *scene.tunnel_entry_m + past) return frame;
  }
  return -1;
}

// Speed along the drive, m/s, from the sensor's positions `dt` apart.
double speed_at(const Trajectory& drive, double time, double dt = 0.01) {
  return (drive.sensor_pose(time + 0.5 * dt).translation() -
          drive.sensor_pose(time - 0.5 * dt).translation())
             .norm() /
         dt;
}

bool same_bytes(const std::vector<SimFrame>& a, const std::vector<SimFrame>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t f = 0; f < a.size(); ++f) {
    const auto& pa = a[f].scan.points;
    const auto& pb = b[f].scan.points;
    if (pa.size() != pb.size() || a[f].labels != b[f].labels) return false;
    if (std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(ScanPoint)) != 0) return false;
  }
  return true;
}

bool same_scene(const World& a, const World& b) {
  if (a.tiles.size() != b.tiles.size() || a.plants.size() != b.plants.size() ||
      a.moving_cars.size() != b.moving_cars.size())
    return false;
  for (auto ia = a.tiles.begin(), ib = b.tiles.begin(); ia != a.tiles.end(); ++ia, ++ib) {
    if (ia->first != ib->first || ia->second.vertices != ib->second.vertices ||
        ia->second.triangle_surfaces != ib->second.triangle_surfaces)
      return false;
  }
  for (std::size_t i = 0; i < a.plants.size(); ++i) {
    if (a.plants[i].base != b.plants[i].base || a.plants[i].prototype != b.plants[i].prototype)
      return false;
  }
  for (std::size_t i = 0; i < a.moving_cars.size(); ++i) {
    if (a.moving_cars[i].motion.start_s != b.moving_cars[i].motion.start_s) return false;
  }
  return true;
}

class EveryScenario : public ::testing::TestWithParam<ScenarioKind> {};

}  // namespace

TEST_P(EveryScenario, GeneratesLabelledScans) {
  const std::vector<SimFrame>& frames = frames_of(GetParam());
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kFrames));
  for (const SimFrame& frame : frames) {
    EXPECT_GT(frame.scan.points.size(), 5000u);
    ASSERT_EQ(frame.labels.size(), frame.scan.points.size());
    for (uint32_t label : frame.labels)
      ASSERT_NE(label_class(label), SemanticClass::kUnlabeled);
  }
  // The sensor moves forward along x from frame to frame, at about the scenario's speed.
  const Eigen::Vector3d step =
      (frames[0].sensor_pose.inverse() * frames[1].sensor_pose).translation();
  EXPECT_GT(step.x(), 0.05 * default_scenario(GetParam()).cruise_speed_mps);
  EXPECT_LT(std::abs(step.y()), 0.2 * step.x());
  // Every point has its exact geometry, for the scan's true observability.
  for (const SimFrame& frame : frames) {
    ASSERT_EQ(frame.exact_points.size(), frame.labels.size());
    ASSERT_EQ(frame.exact_normals.size(), frame.labels.size());
  }
}

// The scans, the ground truth and the motion sensors follow one smooth curve in every scenario.
TEST_P(EveryScenario, DrivesTheSmoothTrajectory) {
  const GeneratedScene scene = generate_scene(request_for(GetParam(), 3));
  ASSERT_NE(scene.motion, nullptr);
  EXPECT_EQ(scene.trajectory, scene.motion);
}

INSTANTIATE_TEST_SUITE_P(Sim, EveryScenario,
                         ::testing::Values(ScenarioKind::kUrban, ScenarioKind::kHighway,
                                           ScenarioKind::kTunnel, ScenarioKind::kVegetation,
                                           ScenarioKind::kLoop, ScenarioKind::kCorridor),
                         [](const auto& info) { return kind_name(info.param); });

TEST(SimScenarios, SameSeedSameBytesOtherSeedOtherScene) {
  // Scans (wind, shaking and noise included) of the scenario with the most randomness...
  EXPECT_TRUE(
      same_bytes(simulate(ScenarioKind::kVegetation, 3), frames_of(ScenarioKind::kVegetation)));
  // ...and the scene of the one with the most kinds of objects.
  const GeneratedScene first = generate_scene(request_for(ScenarioKind::kUrban, 3));
  const GeneratedScene again = generate_scene(request_for(ScenarioKind::kUrban, 3));
  const GeneratedScene other = generate_scene(request_for(ScenarioKind::kUrban, 4));
  EXPECT_TRUE(same_scene(*first.world, *again.world));
  EXPECT_FALSE(same_scene(*first.world, *other.world));
}

TEST(SimScenarios, VegetationShareSetsTheScenariosApart) {
  const double vegetation = character_of(ScenarioKind::kVegetation).vegetation_share();
  const double urban = character_of(ScenarioKind::kUrban).vegetation_share();
  const double highway = character_of(ScenarioKind::kHighway).vegetation_share();
  const double corridor = character_of(ScenarioKind::kCorridor).vegetation_share();
  EXPECT_GT(vegetation, 0.35);
  EXPECT_GT(vegetation, 2.5 * urban);
  EXPECT_GT(urban, 0.01);
  EXPECT_LT(highway, 0.15);
  EXPECT_EQ(corridor, 0.0);
}

// Both tunnels start on open road, enter the portal at the cruise speed, brake to 5 m/s inside
// and pull away again, smoothly.
TEST(SimScenarios, TunnelsAreEnteredAtSpeedAndBrakeInside) {
  for (const std::string name : {"tunnel", "bare_tunnel"}) {
    SceneRequest request = request_for(ScenarioKind::kTunnel, 3, 600);
    request.scenario = named_scenario(name);
    const GeneratedScene scene = generate_scene(request);
    const Trajectory& drive = *scene.trajectory;
    ASSERT_TRUE(scene.tunnel_entry_m.has_value()) << name;
    EXPECT_GE(*scene.tunnel_entry_m, 90.0);
    EXPECT_LE(*scene.tunnel_entry_m, 120.0);
    ASSERT_EQ(scene.speed_changes.size(), 2u) << name;
    const double portal_time = *scene.tunnel_entry_m / 15.0;
    EXPECT_NEAR(speed_at(drive, 0.0), 15.0, 0.01) << name;
    EXPECT_NEAR(speed_at(drive, portal_time), 15.0, 0.01) << name;
    double slowest = 1e9, steepest = 0.0, previous = speed_at(drive, 0.0);
    for (double t = 0.05; t < 60.0; t += 0.05) {
      const double speed = speed_at(drive, t);
      slowest = std::min(slowest, speed);
      steepest = std::max(steepest, std::abs(speed - previous) / 0.05);
      previous = speed;
    }
    EXPECT_NEAR(slowest, 5.0, 0.05) << name;
    EXPECT_LE(steepest, 1.05) << name << ": at most 1 m/s^2 and no jumps";
    EXPECT_NEAR(speed_at(drive, 59.0), 15.0, 0.1) << name << ": back at speed within a minute";
  }
}

// Deep inside the bare tunnel smooth walls give no constraint along the road; the furnished
// tunnel's lamps, signs, niches and fans do.
TEST(SimScenarios, TheBareTunnelFixesNothingAlongTheRoadTheFurnishedOneDoes) {
  double weakest_sigma[2];
  for (int furnished = 0; furnished < 2; ++furnished) {
    SceneRequest request = request_for(ScenarioKind::kTunnel, 3, 300);
    request.scenario = named_scenario(furnished ? "tunnel" : "bare_tunnel");
    const GeneratedScene scene = generate_scene(request);
    const int frame = frame_inside(scene, 110.0);  // the portal out of the VLP-16's range
    ASSERT_GT(frame, 0);
    const std::vector<SimFrame> frames{simulator_for(scene, 3).render(frame)};
    const Character tunnel = character_of(frames);
    const WeakestTranslation weakest = weakest_translation(scan_information(frames[0], 0.02));
    weakest_sigma[furnished] = weakest.sigma_m;
    std::printf("[ measured ] %s, frame %d: weakest translation %.4f m along (%.2f, %.2f, %.2f)\n",
                request.scenario.name.c_str(), frame, weakest.sigma_m, weakest.direction.x(),
                weakest.direction.y(), weakest.direction.z());
    EXPECT_GT(std::abs(weakest.direction.x()), 0.99) << "along the road";
    const long walls = tunnel.structure_left + tunnel.structure_right;
    EXPECT_GT(tunnel.share(SemanticClass::kOtherStructure), 0.3);
    EXPECT_GT(tunnel.structure_left, 0.3 * walls);
    EXPECT_GT(tunnel.structure_right, 0.3 * walls);
    const double facing = double(tunnel.facing_along_road) / tunnel.non_ground;
    if (furnished) {
      EXPECT_GT(tunnel.share(SemanticClass::kTrafficSign), 0.0);
      EXPECT_GT(tunnel.share(SemanticClass::kOtherObject), 0.0);
    } else {
      EXPECT_EQ(tunnel.share(SemanticClass::kTerrain), 0.0);
      EXPECT_LT(facing, 0.01);
    }
  }
  EXPECT_GT(weakest_sigma[0], 10.0 * weakest_sigma[1]);
}

// A robot's drive: 0.6 m above the floor at 1.5 m/s, standing still for a while, and a 90 deg
// turn into a second corridor; walls, doors and floor only.
TEST(SimScenarios, CorridorTurnsIntoASecondCorridorWithStops) {
  const GeneratedScene scene = generate_scene(request_for(ScenarioKind::kCorridor, 3, 400));
  const Trajectory& drive = *scene.trajectory;
  EXPECT_NEAR(drive.sensor_pose(0.0).translation().z(), 0.6, 1e-9);
  double fastest = 0.0, standing = 0.0;
  for (double t = 0.0; t < 40.0; t += 0.05) {
    const double speed = speed_at(drive, t);
    fastest = std::max(fastest, speed);
    standing += speed < 1e-6 ? 0.05 : 0.0;
  }
  EXPECT_NEAR(fastest, 1.5, 1e-3);
  EXPECT_GE(standing, 4.0) << "two stops of 2-4 s";
  const Eigen::Matrix3d turned =
      drive.sensor_pose(0.0).linear().transpose() * drive.sensor_pose(40.0).linear();
  EXPECT_NEAR(std::abs(std::atan2(turned(1, 0), turned(0, 0))), 0.5 * M_PI, 1e-3);
  const Character corridor = character_of(ScenarioKind::kCorridor);
  EXPECT_GT(corridor.share(SemanticClass::kBuilding), 0.8);
  EXPECT_GT(corridor.share(SemanticClass::kOtherGround), 0.01);
  EXPECT_EQ(corridor.share(SemanticClass::kBuilding) + corridor.share(SemanticClass::kOtherGround),
            1.0);
  SceneRequest recorded = request_for(ScenarioKind::kCorridor, 3);
  recorded.trajectory_times = {0.0, 0.1, 0.2};
  recorded.trajectory_poses.assign(3, Eigen::Isometry3d::Identity());
  EXPECT_THROW(generate_scene(recorded), std::invalid_argument);
}

TEST(SimScenarios, HighwayIsBarriersWallsAndShrubsAlongTheRoad) {
  const Character highway = character_of(ScenarioKind::kHighway);
  const Character urban = character_of(ScenarioKind::kUrban);
  EXPECT_EQ(highway.share(SemanticClass::kBuilding), 0.0);
  EXPECT_EQ(highway.share(SemanticClass::kCar), 0.0);  // nobody parks on a highway
  // Guard rails and concrete barriers (fence), noise walls (other-structure), berms and cuttings
  // (terrain), shrubs and trees, traffic, the odd sign.
  EXPECT_GT(highway.non_ground_share({SemanticClass::kFence, SemanticClass::kOtherStructure,
                                      SemanticClass::kTerrain, SemanticClass::kVegetation,
                                      SemanticClass::kTrunk, SemanticClass::kMovingCar,
                                      SemanticClass::kPole, SemanticClass::kTrafficSign}),
            0.99);
  EXPECT_GT(highway.non_ground_share({SemanticClass::kFence, SemanticClass::kOtherStructure}), 0.4);
  // Surfaces facing along the road are what pins the motion along it: the city has many more.
  const double highway_facing = double(highway.facing_along_road) / highway.non_ground;
  const double urban_facing = double(urban.facing_along_road) / urban.non_ground;
  EXPECT_GT(urban_facing, 2.0 * highway_facing);
}

TEST(SimScenarios, UrbanHasTheThingsOfAStreet) {
  const Character urban = character_of(ScenarioKind::kUrban);
  EXPECT_GT(urban.share(SemanticClass::kBuilding), 0.05);
  EXPECT_GT(urban.share(SemanticClass::kSidewalk), 0.01);
  EXPECT_GT(urban.share(SemanticClass::kCar) + urban.share(SemanticClass::kMovingCar), 0.01);
  EXPECT_GT(urban.share(SemanticClass::kPole), 0.0);
}

TEST(SimScenarios, LoopComesBackToItsStart) {
  const int frames = 250;
  const GeneratedScene scene = generate_scene(request_for(ScenarioKind::kLoop, 3, frames));
  const Trajectory& trajectory = *scene.trajectory;
  const Eigen::Isometry3d start = trajectory.sensor_pose(0.0);
  const Eigen::Isometry3d back = trajectory.sensor_pose(trajectory.frame_time(frames));
  EXPECT_LT((back.translation() - start.translation()).norm(), 1e-6);
  double farthest = 0.0;
  for (int frame = 0; frame < frames; frame += 10)
    farthest = std::max(
        farthest,
        (trajectory.sensor_pose(trajectory.frame_time(frame)).translation() - start.translation())
            .norm());
  EXPECT_GT(farthest, 40.0);
}

TEST(SimScenarios, ALoopDrivenThreeTimesPassesItsStartEachLap) {
  const int frames = 600;
  SceneRequest request = request_for(ScenarioKind::kLoop, 3, frames);
  request.laps = 3;
  const GeneratedScene scene = generate_scene(request);
  const Trajectory& trajectory = *scene.trajectory;
  const Eigen::Vector3d start = trajectory.sensor_pose(0.0).translation();
  for (int lap = 1; lap <= 3; ++lap) {
    const double t = trajectory.frame_time(lap * frames / 3);
    EXPECT_LT((trajectory.sensor_pose(t).translation() - start).norm(), 0.5) << "lap " << lap;
  }
  const double t = trajectory.frame_time(frames / 6);
  EXPECT_GT((trajectory.sensor_pose(t).translation() - start).norm(), 20.0) << "half a lap";
  request.laps = 0;
  EXPECT_THROW(generate_scene(request), std::invalid_argument);
}

// The same scene seed, another seed: the same place driven the same way, with other moving
// objects and other noise.
TEST(SimScenarios, SceneSeedFixesThePlaceAndTheDriveSeedTheRest) {
  SceneRequest first = request_for(ScenarioKind::kUrban, 1);
  first.scene_seed = 7;
  SceneRequest second = first;
  second.seed = 2;
  const GeneratedScene a = generate_scene(first);
  const GeneratedScene b = generate_scene(second);
  ASSERT_EQ(a.world->tiles.size(), b.world->tiles.size());
  for (auto ia = a.world->tiles.begin(), ib = b.world->tiles.begin(); ia != a.world->tiles.end();
       ++ia, ++ib) {
    EXPECT_EQ(ia->second.vertices, ib->second.vertices);
  }
  ASSERT_EQ(a.world->plants.size(), b.world->plants.size());
  for (std::size_t i = 0; i < a.world->plants.size(); ++i)
    EXPECT_EQ(a.world->plants[i].base, b.world->plants[i].base);
  for (int frame = 0; frame < 3; ++frame) {
    const double t = a.trajectory->frame_time(frame);
    EXPECT_TRUE(a.trajectory->sensor_pose(t).isApprox(b.trajectory->sensor_pose(t), 1e-12));
  }
  bool cars_differ = a.world->moving_cars.size() != b.world->moving_cars.size();
  for (std::size_t i = 0; !cars_differ && i < a.world->moving_cars.size(); ++i)
    cars_differ = a.world->moving_cars[i].motion.start_s != b.world->moving_cars[i].motion.start_s;
  EXPECT_TRUE(cars_differ);
  // Without a scene seed, the seed is the scene's too: seed 7 builds scene seed 7's place.
  const GeneratedScene plain = generate_scene(request_for(ScenarioKind::kUrban, 7));
  ASSERT_EQ(plain.world->plants.size(), a.world->plants.size());
  for (std::size_t i = 0; i < a.world->plants.size(); ++i)
    EXPECT_EQ(plain.world->plants[i].base, a.world->plants[i].base);
}

TEST(SimScenarios, RoughRoadShakesTheSensor) {
  // Roll over one second, in steps shorter than a sweep.
  auto roll_spread = [](ScenarioKind kind) {
    const GeneratedScene scene = generate_scene(request_for(kind, 3, 10));
    double low = 1e9, high = -1e9;
    for (int k = 0; k <= 100; ++k) {
      const Eigen::Matrix3d r = scene.trajectory->sensor_pose(0.01 * k).linear();
      const double roll = std::atan2(r(2, 1), r(2, 2)) * 180.0 / M_PI;
      low = std::min(low, roll);
      high = std::max(high, roll);
    }
    return high - low;
  };
  EXPECT_GT(roll_spread(ScenarioKind::kVegetation), 0.5);
  EXPECT_LT(roll_spread(ScenarioKind::kUrban), 0.05);
}
