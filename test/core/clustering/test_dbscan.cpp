#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <set>

#include "adaptive_lego_loam/core/clustering/dbscan.h"

using namespace adaptive_lego_loam;

namespace {

// `count` points spread uniformly in a cube of side `side` around (cx, cy, cz).
void add_blob(std::vector<ScanPoint>& points, float cx, float cy, float cz, int count, float side,
              std::mt19937& rng) {
  std::uniform_real_distribution<float> offset(-side / 2, side / 2);
  for (int i = 0; i < count; ++i) {
    ScanPoint p;
    p.x = cx + offset(rng);
    p.y = cy + offset(rng);
    p.z = cz + offset(rng);
    points.push_back(p);
  }
}

ScanPoint at(float x, float y, float z) {
  ScanPoint p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

}  // namespace

TEST(Dbscan, TwoDenseBlobsAndASparseOutlier) {
  std::mt19937 rng(5);
  std::vector<ScanPoint> points;
  add_blob(points, 0, 0, 0, 30, 0.4f, rng);
  add_blob(points, 5, 0, 0, 30, 0.4f, rng);
  points.push_back(at(20, 20, 0));  // alone: no neighbour within eps
  const std::vector<int32_t> label = dbscan(points, {0.75, 5});
  ASSERT_EQ(label.size(), points.size());
  EXPECT_EQ(label.back(), kDbscanNoise);
  EXPECT_EQ(std::set<int32_t>(label.begin(), label.begin() + 30), std::set<int32_t>{label[0]});
  EXPECT_EQ(std::set<int32_t>(label.begin() + 30, label.begin() + 60),
            std::set<int32_t>{label[30]});
  EXPECT_NE(label[0], label[30]);
  EXPECT_GE(label[0], 0);
  EXPECT_GE(label[30], 0);
}

TEST(Dbscan, MinSamplesCountsThePointItself) {
  // Five points within eps of each other: each has 5 in its neighbourhood, itself included.
  std::vector<ScanPoint> five;
  for (int i = 0; i < 5; ++i)
    five.push_back(at(0.1f * i, 0, 0));
  const std::vector<int32_t> clustered = dbscan(five, {0.75, 5});
  EXPECT_EQ(std::set<int32_t>(clustered.begin(), clustered.end()), std::set<int32_t>{0});
  five.pop_back();
  const std::vector<int32_t> too_few = dbscan(five, {0.75, 5});
  EXPECT_EQ(std::set<int32_t>(too_few.begin(), too_few.end()), std::set<int32_t>{kDbscanNoise});
}

TEST(Dbscan, BorderPointJoinsButDoesNotExpand) {
  // A dense line of points 0.1 m apart ending at x = 1; a point at x = 1.7 is within eps of the
  // last core point but has too few neighbours to be core; one more at x = 2.4 is within eps of
  // the border point only, and stays noise. Whether the border point is met first (as noise) or
  // through the cluster, it ends in the cluster.
  std::vector<ScanPoint> line;
  for (int i = 0; i <= 10; ++i)
    line.push_back(at(0.1f * i, 0, 0));
  for (bool border_first : {false, true}) {
    SCOPED_TRACE(border_first ? "border point first" : "border point last");
    std::vector<ScanPoint> points = {at(1.7f, 0, 0), at(2.4f, 0, 0)};
    points.insert(border_first ? points.end() : points.begin(), line.begin(), line.end());
    const int border = border_first ? 0 : 11, outlier = border + 1, core = border_first ? 2 : 0;
    const std::vector<int32_t> label = dbscan(points, {0.75, 5});
    EXPECT_GE(label[core], 0);
    EXPECT_EQ(label[border], label[core]);
    EXPECT_EQ(label[outlier], kDbscanNoise);
  }
}

TEST(Dbscan, NonFinitePointsAreNoise) {
  std::vector<ScanPoint> points;
  for (int i = 0; i < 6; ++i)
    points.push_back(at(0.1f * i, 0, 0));
  points.push_back(at(std::numeric_limits<float>::quiet_NaN(), 0, 0));
  const std::vector<int32_t> label = dbscan(points, {0.75, 5});
  EXPECT_EQ(label[6], kDbscanNoise);
  EXPECT_EQ(label[0], 0);
  EXPECT_TRUE(dbscan({}, {0.75, 5}).empty());
}
