// The vertical-structure prior's patches: walls found, floors, slanted planes and single rows not.

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <vector>

#include "adaptive_lego_loam/core/mapping/vertical_structure.h"

using namespace adaptive_lego_loam;

namespace {

void add(Cloud& cloud, const Eigen::Vector3d& p) {
  CloudPoint point;
  point.getVector3fMap() = p.cast<float>();
  cloud.push_back(point);
}

// A floor 1.7 m below the sensor and two walls 5.7 m high, at x = 5 and y = 4, every 0.1 m.
Cloud floor_and_two_walls() {
  Cloud cloud;
  for (double u = -4.0; u <= 4.0; u += 0.1) {
    for (double v = -1.7; v <= 4.0; v += 0.1) {
      add(cloud, {u, v + 0.3, -1.7});
      add(cloud, {5.0, u, v});
      add(cloud, {u, 4.0, v});
    }
  }
  return cloud;
}

// A wall at y = 4 from `bottom` to `top` (m, sensor frame), `length` m long.
Cloud wall(double bottom, double top, double length = 10.0) {
  Cloud cloud;
  for (double u = -0.5 * length; u <= 0.5 * length; u += 0.1) {
    for (double v = bottom; v <= top; v += 0.1)
      add(cloud, {u, 4.0, v});
  }
  return cloud;
}

}  // namespace

TEST(VerticalStructure, FindsBothWallsAndNotTheFloor) {
  const std::vector<Eigen::Vector3d> normals =
      wall_normals(floor_and_two_walls(), Eigen::Matrix3d::Identity(), 10.0);
  int facing_x = 0, facing_y = 0;
  for (const Eigen::Vector3d& n : normals) {
    EXPECT_NEAR(n.norm(), 1.0, 1e-9);
    EXPECT_LT(std::fabs(n.z()), 1e-3);
    if (std::fabs(n.x()) > 0.999) ++facing_x;
    if (std::fabs(n.y()) > 0.999) ++facing_y;
  }
  EXPECT_EQ(facing_x + facing_y, static_cast<int>(normals.size()));
  EXPECT_GT(facing_x, 10);
  EXPECT_GT(facing_y, 10);
}

TEST(VerticalStructure, APlaneTiltedBeyondTheLimitIsNoWall) {
  // A wall leaning 20 deg: a wall within 30 deg of vertical, not within 10.
  Cloud cloud;
  const double lean = 20.0 * M_PI / 180.0;
  for (double u = -5.0; u <= 5.0; u += 0.1) {
    for (double v = 0.0; v <= 4.0; v += 0.1)
      add(cloud, {5.0 + v * std::sin(lean), u, v * std::cos(lean)});
  }
  EXPECT_TRUE(wall_normals(cloud, Eigen::Matrix3d::Identity(), 10.0).empty());
  EXPECT_FALSE(wall_normals(cloud, Eigen::Matrix3d::Identity(), 30.0).empty());
}

TEST(VerticalStructure, TheRotationDecidesWhatIsVertical) {
  // The same upright walls seen by a sensor the map knows is rolled 20 deg: in the map frame they
  // lean, so none is a wall.
  const Eigen::Matrix3d rolled = Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()).matrix();
  const Cloud upright = wall(-1.5, 4.0);
  EXPECT_FALSE(wall_normals(upright, Eigen::Matrix3d::Identity(), 10.0).empty());
  EXPECT_TRUE(wall_normals(upright, rolled, 10.0).empty());
}

TEST(VerticalStructure, OneRowAcrossAWallIsNoPatch) {
  // A single ring's points on a wall lie on a line: no plane to take a normal from.
  Cloud cloud;
  for (double u = -4.0; u <= 4.0; u += 0.02)
    add(cloud, {5.0, u, 0.5});
  EXPECT_TRUE(wall_normals(cloud, Eigen::Matrix3d::Identity(), 10.0).empty());
}

TEST(VerticalStructure, WhatStaysBelowTheSensorIsNoWall) {
  // A barrier 0.8 m high beside the road (the sensor 1.7 m up): near the ground, surfaces that
  // look upright often lean (barriers, curbs, embankments).
  EXPECT_TRUE(wall_normals(wall(-1.7, -0.9, 60.0), Eigen::Matrix3d::Identity(), 10.0).empty());
  EXPECT_FALSE(wall_normals(wall(-1.7, 3.0, 60.0), Eigen::Matrix3d::Identity(), 10.0).empty());
}

TEST(VerticalStructure, AFewPatchesAreNotEnough) {
  // Two 1 m cells of wall above the sensor: too little to steer the map by.
  Cloud cloud;
  for (double u = 0.05; u < 2.0; u += 0.1) {
    for (double v = 0.05; v < 1.0; v += 0.1)
      add(cloud, {u, 4.5, v});
  }
  EXPECT_TRUE(wall_normals(cloud, Eigen::Matrix3d::Identity(), 10.0).empty());
}

TEST(VerticalStructure, APatchRisingAboveATiltedSensorCountsThoughItsCubeStartsBelow) {
  // Twenty patches of a wall at x = 5.5, each in a cube that starts below the sensor (z from -1),
  // the sensor rolled 40 deg: the first cube's lowest corner lies below the sensor in the map
  // frame, its points' mean above it. All twenty are walls (twenty, the least that counts).
  Cloud cloud;
  for (int k = 0; k < 20; ++k) {
    for (double y = k + 0.05; y < k + 1.0; y += 0.1) {
      for (double z = -0.45; z < 0.0; z += 0.1)
        add(cloud, {5.5, y, z});
    }
  }
  const Eigen::Matrix3d rolled =
      Eigen::AngleAxisd(40.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_EQ(wall_normals(cloud, rolled, 5.0).size(), 20u);
}
