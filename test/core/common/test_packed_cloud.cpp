// Packed keyframe clouds: 8 bytes a point, each coordinate within half the grid step.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "adaptive_lego_loam/core/common/packed_cloud.h"

using namespace adaptive_lego_loam;

namespace {

Cloud scan_like(float extent, int count) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> coordinate(-extent, extent);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    CloudPoint p;
    p.x = coordinate(random);
    p.y = coordinate(random);
    p.z = 0.05f * coordinate(random);
    p.intensity = static_cast<float>(i % 64);  // a row
    cloud.push_back(p);
  }
  return cloud;
}

}  // namespace

TEST(PackedCloud, EveryPointWithinHalfAStepOfTheOriginal) {
  const Cloud cloud = scan_like(120.f, 5000);
  const PackedCloud packed(cloud);
  ASSERT_EQ(packed.size(), cloud.size());
  EXPECT_LE(packed.bytes(), 8 * cloud.size());
  EXPECT_LT(packed.step(), 0.004f) << "a 120 m scan on a grid under 4 mm";
  const CloudPtr unpacked = packed.unpack();
  ASSERT_EQ(unpacked->size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f error = (*unpacked)[i].getVector3fMap() - cloud[i].getVector3fMap();
    ASSERT_LE(error.cwiseAbs().maxCoeff(), 0.5f * packed.step() + 1e-5f) << "point " << i;
    ASSERT_FLOAT_EQ((*unpacked)[i].intensity, cloud[i].intensity);
  }
}

TEST(PackedCloud, UnpacksMovedByAPose) {
  const Cloud cloud = scan_like(30.f, 100);
  const PackedCloud packed(cloud);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 0.1, 1.0).normalized()).matrix();
  pose.translation() = Eigen::Vector3d(100.0, -50.0, 3.0);
  Cloud moved;
  moved.push_back(CloudPoint());  // appended to what is there
  packed.unpack(pose, moved);
  ASSERT_EQ(moved.size(), cloud.size() + 1);
  const CloudPtr reference = transform_cloud(cloud, pose);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_LT(((moved[i + 1].getVector3fMap() - (*reference)[i].getVector3fMap())).norm(),
              packed.step() + 1e-4f);
  }
}

TEST(PackedCloud, NonFinitePointsAreLeftOutAndTinyCloudsKeepAFineGrid) {
  Cloud cloud;
  CloudPoint p;
  p.x = 0.001f;
  cloud.push_back(p);
  p.x = std::numeric_limits<float>::quiet_NaN();
  cloud.push_back(p);
  const PackedCloud packed(cloud);
  ASSERT_EQ(packed.size(), 1u);
  EXPECT_NEAR((*packed.unpack())[0].x, 0.001f, 1e-4f);
  EXPECT_TRUE(PackedCloud(Cloud()).empty());
}
