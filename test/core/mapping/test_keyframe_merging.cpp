// Old keyframes merged a group at a time: the clouds in one keyframe, the poses in all, and a
// place driven again not stored twice.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/mapping/keyframe_merging.h"

using namespace adaptive_lego_loam;

namespace {

MappingParams merging(int group, int after) {
  MappingParams params;
  params.keyframe_merge_group = group;
  params.keyframe_merge_after = after;
  params.corner_voxel = 0.2;
  params.surface_voxel = 0.4;
  params.keyframe_distance = 1.0;
  return params;
}

// A wall along x at y = 5, 20 m long, seen from a keyframe at (x, 0): its points in the sensor
// frame, one every 10 cm.
Cloud wall_seen_from(double x) {
  Cloud cloud;
  for (double along = -10.0; along <= 10.0; along += 0.1) {
    CloudPoint p;
    p.x = static_cast<float>(along - x);
    p.y = 5.f;
    p.z = 0.f;
    cloud.push_back(p);
  }
  return cloud;
}

// Keyframes `spacing` m apart along x from x = 0, each seeing the wall; then `back` more
// driving the same road again from x = `shift`, `across` m to its side.
std::vector<Keyframe> drive(int count, int back = 0, double shift = 0.0, double across = 0.0,
                            double spacing = 1.0) {
  std::vector<Keyframe> keyframes;
  for (int i = 0; i < count + back; ++i) {
    Keyframe keyframe;
    keyframe.index = i;
    const bool again = i >= count;
    const double x = spacing * (again ? i - count : i) + (again ? shift : 0.0);
    keyframe.pose.translation() = Eigen::Vector3d(x, again ? across : 0.0, 0.0);
    keyframe.corners = pack(Cloud());
    keyframe.surfaces = pack(wall_seen_from(x));
    keyframes.push_back(keyframe);
  }
  return keyframes;
}

int keyframes_with_clouds(const std::vector<Keyframe>& keyframes) {
  int count = 0;
  for (const Keyframe& keyframe : keyframes)
    count += keyframe.has_clouds();
  return count;
}

// Drives 30 keyframes, then the same road again from `shift` along and `across` it; merges
// groups of 5 older than the newest 5. Returns how many merged keyframes of the second pass kept
// a cloud (five groups of it are merged).
int stored_on_second_pass(double shift, double across, std::vector<Keyframe>* keyframes = nullptr) {
  std::vector<Keyframe> twice = drive(30, 30, shift, across);
  KeyframeMerger merger(merging(5, 5));
  merger.merge_old(twice);
  EXPECT_EQ(merger.merged_until(), 55);
  int stored_again = 0;
  for (int i = 30; i < merger.merged_until(); ++i)
    stored_again += twice[i].has_clouds();
  if (keyframes) *keyframes = std::move(twice);
  return stored_again;
}

}  // namespace

TEST(KeyframeMerging, OnlyGroupsOlderThanTheRecentWindowAreMerged) {
  std::vector<Keyframe> keyframes = drive(25);
  KeyframeMerger merger(merging(5, 12));
  EXPECT_EQ(merger.merge_old(keyframes), 2);  // keyframes 0-9; 10-14 are among the newest 12
  EXPECT_EQ(merger.merged_until(), 10);
  EXPECT_EQ(keyframes_with_clouds(keyframes), 2 + 15);
  EXPECT_TRUE(keyframes[2].has_clouds()) << "a group's middle keyframe holds its clouds";
  EXPECT_TRUE(keyframes[7].has_clouds());
  EXPECT_FALSE(keyframes[0].has_clouds());
  EXPECT_EQ(merger.merge_old(keyframes), 0) << "nothing new is old enough";
  for (int i = 0; i < 25; ++i)
    EXPECT_DOUBLE_EQ(keyframes[i].pose.translation().x(), i) << "poses stay";
}

TEST(KeyframeMerging, TheMergedCloudIsTheGroupsCloudsInTheAnchorsFrameVoxelFiltered) {
  std::vector<Keyframe> keyframes = drive(20);
  KeyframeMerger merger(merging(5, 10));
  merger.merge_old(keyframes);
  const Keyframe& anchor = keyframes[2];
  const CloudPtr merged = anchor.surfaces->unpack(anchor.pose);  // map frame
  // Five views of one wall, 1 m apart, voxel-filtered at 0.4 m: about 24 m of wall (20 m seen
  // from x = 0 ... 4), two or three centroids per 0.4 m cell along it, not five copies.
  EXPECT_GT(merged->size(), 50u);
  EXPECT_LT(merged->size(), 80u);
  for (const CloudPoint& p : *merged) {
    EXPECT_NEAR(p.y, 5.f, 0.01f);
    EXPECT_GE(p.x, -10.f - 0.01f);
    EXPECT_LE(p.x, 10.f + 0.01f);
  }
}

TEST(KeyframeMerging, APlaceDrivenAgainIsNotStoredTwice) {
  // The second pass over x = 0 ... 29 finds every place stored: its merged groups keep nothing.
  std::vector<Keyframe> twice;
  EXPECT_EQ(stored_on_second_pass(0.0, 0.0, &twice), 0);
  EXPECT_EQ(keyframes_with_clouds(twice), 30 / 5 + 5)
      << "the first pass's six groups, and the newest five, still unmerged";
}

TEST(KeyframeMerging, ASecondPassOffsetAlongAndAcrossTheRoadIsNotStoredTwice) {
  // Its groups' middles fall halfway between the first pass's, 2 m to the side.
  EXPECT_EQ(stored_on_second_pass(2.5, 2.0), 0);
}

TEST(KeyframeMerging, APassAlongAParallelRoadIsStored) {
  // 12 m to the side: beyond half the merge radius (20 m) of the first pass's merged keyframes.
  EXPECT_EQ(stored_on_second_pass(0.0, 12.0), 5)
      << "each of the second pass's five merged groups kept its cloud";
}

TEST(KeyframeMerging, KeyframesCloseTogetherOnNewGroundAreAllStored) {
  // Keyframes 0.2 m apart (a slow tight turn makes them by angle): each group's middle lies 1 m
  // from the previous group's, on ground no earlier pass covered.
  std::vector<Keyframe> keyframes = drive(40, 0, 0.0, 0.0, 0.2);
  KeyframeMerger merger(merging(5, 5));
  EXPECT_EQ(merger.merge_old(keyframes), 7);
  EXPECT_EQ(keyframes_with_clouds(keyframes), 7 + 5) << "every merged group kept its cloud";
}

TEST(KeyframeMerging, AGroupOfOneIsOff) {
  std::vector<Keyframe> keyframes = drive(30);
  KeyframeMerger merger(merging(1, 5));
  EXPECT_EQ(merger.merge_old(keyframes), 0);
  EXPECT_EQ(keyframes_with_clouds(keyframes), 30);
}
