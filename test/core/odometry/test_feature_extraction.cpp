// LeGO-LOAM's feature extraction on constructed rows: which points become edges and surfaces, and
// the occluded and near-parallel points it must not pick.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "adaptive_lego_loam/core/odometry/feature_extraction.h"

using namespace adaptive_lego_loam;

namespace {

struct Segment {
  Eigen::Vector2d a, b;
};

// Distance along the unit ray `dir` from the origin to the segment, or infinity.
double hit(const Segment& s, const Eigen::Vector2d& dir) {
  const Eigen::Vector2d edge = s.b - s.a;
  const double denominator = dir.x() * edge.y() - dir.y() * edge.x();
  if (std::fabs(denominator) < 1e-12) return std::numeric_limits<double>::infinity();
  const double t = (s.a.x() * edge.y() - s.a.y() * edge.x()) / denominator;
  const double u = (s.a.x() * dir.y() - s.a.y() * dir.x()) / denominator;
  return t > 0.0 && u >= 0.0 && u <= 1.0 ? t : std::numeric_limits<double>::infinity();
}

constexpr double kStepDeg = 0.2;

// One row of a segmented cloud: a beam every kStepDeg from `from_deg` to `to_deg` in the sensor's
// horizontal plane, each hitting the nearest wall. `ground` flags the beams within the given
// azimuths as ground.
SegmentedCloud row_of(const std::vector<Segment>& walls, double from_deg, double to_deg,
                      double ground_from_deg = 1e9, double ground_to_deg = -1e9) {
  SegmentedCloud cloud;
  int column = 0;
  for (double deg = from_deg; deg <= to_deg; deg += kStepDeg, ++column) {
    const Eigen::Vector2d dir(std::cos(deg * M_PI / 180.0), std::sin(deg * M_PI / 180.0));
    double range = std::numeric_limits<double>::infinity();
    for (const Segment& wall : walls)
      range = std::min(range, hit(wall, dir));
    if (!std::isfinite(range)) continue;
    ScanPoint p;
    p.x = static_cast<float>(range * dir.x());
    p.y = static_cast<float>(range * dir.y());
    cloud.points.push_back(p);
    cloud.row.push_back(0);
    cloud.info.range.push_back(static_cast<float>(range));
    cloud.info.column.push_back(column);
    cloud.info.ground_flag.push_back(deg >= ground_from_deg && deg <= ground_to_deg);
  }
  // As build_segmented_cloud: five points at each end of a row are left out.
  cloud.info.start_ring_index = {5};
  cloud.info.end_ring_index = {static_cast<int32_t>(cloud.points.size()) - 6};
  return cloud;
}

FeatureSet extract(const SegmentedCloud& cloud, const FeatureParams& params = FeatureParams()) {
  FeatureExtractor extractor(params);
  FeatureSet features;
  extractor.extract(cloud, cloud.points, cloud.outliers, features);
  return features;
}

double range_of(const CloudPoint& p) {
  return std::hypot(p.x, p.y);
}

double distance_to(const CloudPoint& p, double x, double y) {
  return std::hypot(p.x - x, p.y - y);
}

}  // namespace

TEST(FeatureExtraction, TheCornerOfTwoWallsIsTheEdgeAndTheWallsAreSurfaces) {
  // Walls along x = 6 and y = 6, meeting at (6, 6), 45 deg to the left.
  const SegmentedCloud cloud =
      row_of({{{6.0, -10.0}, {6.0, 6.0}}, {{6.0, 6.0}, {-10.0, 6.0}}}, -50.0, 130.0);
  const FeatureSet features = extract(cloud);
  ASSERT_FALSE(features.sharp->empty());
  double nearest = 1e9;
  for (const CloudPoint& p : *features.sharp) {
    nearest = std::min(nearest, distance_to(p, 6.0, 6.0));
    EXPECT_LT(distance_to(p, 6.0, 6.0), 0.2) << "an edge away from the corner";
  }
  EXPECT_LT(nearest, 0.05);
  for (const CloudPoint& p : *features.less_sharp)
    EXPECT_LT(distance_to(p, 6.0, 6.0), 0.2);
  EXPECT_TRUE(features.flat->empty()) << "no ground in this row: no flat surface";
  EXPECT_GT(features.less_flat->size(), 10u) << "the walls are surfaces";
  for (const CloudPoint& p : *features.less_flat)
    EXPECT_FLOAT_EQ(p.intensity, 0.f) << "intensity holds the row";
}

TEST(FeatureExtraction, PointsOfAFarWallBesideANearObjectAreOccludedNotEdges) {
  // An object 0.6 m wide 5 m ahead, a wall 12 m behind it. The object's points are flagged as
  // ground (a low obstacle the ground test took for road), so none of them is an edge whose pick
  // would block its neighbours: what keeps the wall's points beside it from being edges is the
  // occlusion test alone.
  const std::vector<Segment> walls = {{{12.0, -30.0}, {12.0, 30.0}}, {{5.0, -0.3}, {5.0, 0.3}}};
  const SegmentedCloud cloud = row_of(walls, -40.0, 40.0, -3.5, 3.5);
  const FeatureSet features = extract(cloud);
  for (const CloudPoint& p : *features.less_sharp)
    EXPECT_GT(std::fabs(p.y), 1.5) << "an edge on the wall beside the object at y = " << p.y;
  // Without the occlusion test they are taken for edges.
  FeatureParams no_occlusion;
  no_occlusion.occlusion_threshold = 1e3;
  const FeatureSet without_occlusion_test = extract(cloud, no_occlusion);
  int beside_object = 0;
  for (const CloudPoint& p : *without_occlusion_test.less_sharp)
    beside_object += range_of(p) > 11.0 && std::fabs(p.y) < 1.5;
  EXPECT_GT(beside_object, 0);
}

TEST(FeatureExtraction, AWallSeenNearlyEdgeOnGivesNoEdges) {
  // A wall 1.5 m to the left running ahead: beams below ~10 deg of azimuth meet it at a grazing
  // angle, where the range jumps by more than 2 % from beam to beam; a far wall closes the view.
  const std::vector<Segment> walls = {{{2.0, 1.5}, {60.0, 1.5}}, {{60.0, -20.0}, {60.0, 1.5}}};
  const SegmentedCloud cloud = row_of(walls, -10.0, 60.0);
  auto on_grazing_stretch = [](const CloudPoint& p) {
    const double azimuth_deg = std::atan2(p.y, p.x) * 180.0 / M_PI;
    return std::fabs(p.y - 1.5f) < 0.01 && azimuth_deg > 1.5 && azimuth_deg < 9.0;
  };
  const FeatureSet features = extract(cloud);
  for (const CloudPoint& p : *features.less_sharp)
    EXPECT_FALSE(on_grazing_stretch(p)) << "an edge at x = " << p.x;
  FeatureParams no_parallel_test;
  no_parallel_test.parallel_threshold = 10.0;
  int grazing_edges = 0;
  const FeatureSet without_parallel_test = extract(cloud, no_parallel_test);
  for (const CloudPoint& p : *without_parallel_test.less_sharp)
    grazing_edges += on_grazing_stretch(p);
  EXPECT_GT(grazing_edges, 0);
}

TEST(FeatureExtraction, OnlyGroundPointsAreFlatAndEdgesAreNeverGround) {
  // A straight wall, the beams between -20 and 20 deg flagged as ground.
  const SegmentedCloud cloud = row_of({{{8.0, -30.0}, {8.0, 30.0}}}, -60.0, 60.0, -20.0, 20.0);
  const FeatureSet features = extract(cloud);
  ASSERT_FALSE(features.flat->empty());
  EXPECT_LE(features.flat->size(), 6u * 4u) << "at most flat_per_sector in each of 6 sectors";
  for (const CloudPoint& p : *features.flat) {
    const double azimuth_deg = std::atan2(p.y, p.x) * 180.0 / M_PI;
    EXPECT_LE(std::fabs(azimuth_deg), 20.0 + 1e-6);
  }
  for (const CloudPoint& p : *features.less_sharp) {
    const double azimuth_deg = std::atan2(p.y, p.x) * 180.0 / M_PI;
    EXPECT_GT(std::fabs(azimuth_deg), 20.0);
  }
}

TEST(FeatureExtraction, EveryPickedEdgeBlocksItsNeighbours) {
  // A saw-tooth wall: an edge every 0.5 m, far more than the 2 sharp + 20 less sharp a sector
  // takes.
  std::vector<Segment> teeth;
  for (double y = -10.0; y < 10.0; y += 0.5)
    teeth.push_back({{8.0 + (std::lround(y * 2) % 2 ? 0.3 : 0.0), y},
                     {8.0 + (std::lround(y * 2) % 2 ? 0.0 : 0.3), y + 0.5}});
  const SegmentedCloud cloud = row_of(teeth, -45.0, 45.0);
  const FeatureSet features = extract(cloud);
  EXPECT_LE(features.sharp->size(), 6u * 2u);
  EXPECT_LE(features.less_sharp->size(), 6u * 20u);
  // No two picked edges are neighbours within 5 beams of each other.
  std::vector<double> azimuths;
  for (const CloudPoint& p : *features.less_sharp)
    azimuths.push_back(std::atan2(p.y, p.x) * 180.0 / M_PI);
  std::sort(azimuths.begin(), azimuths.end());
  for (std::size_t i = 1; i < azimuths.size(); ++i)
    EXPECT_GT(azimuths[i] - azimuths[i - 1], 5 * kStepDeg + 1e-6);
}

TEST(FeatureExtraction, OutliersAreTheOnesGivenAsTheSweepWasStraightened) {
  SegmentedCloud cloud = row_of({{{8.0, -30.0}, {8.0, 30.0}}}, -60.0, 60.0);
  ScanPoint raw;
  raw.x = 3.f;
  cloud.outliers = {raw};
  ScanPoint deskewed = raw;
  deskewed.x = 2.5f;  // where de-skewing moved it
  FeatureExtractor extractor{FeatureParams()};
  FeatureSet features;
  extractor.extract(cloud, cloud.points, {deskewed}, features);
  ASSERT_EQ(features.outliers->size(), 1u);
  EXPECT_FLOAT_EQ((*features.outliers)[0].x, 2.5f);
  EXPECT_FLOAT_EQ((*features.outliers)[0].intensity, -1.f) << "outliers have no row";
}

// The choice depends on the ranges, not the positions: made ahead on the cloud as segmented and
// assembled from the de-skewed points, it gives extract()'s clouds bit for bit, the less-flat
// voxel filter's history included (two scans through each extractor).
TEST(FeatureExtraction, AChoiceMadeAheadAssemblesToTheSameClouds) {
  const SegmentedCloud first =
      row_of({{{6.0, -10.0}, {6.0, 6.0}}, {{6.0, 6.0}, {-10.0, 6.0}}}, -50.0, 130.0, -20.0, 20.0);
  const SegmentedCloud second = row_of({{{8.0, -30.0}, {8.0, 30.0}}}, -60.0, 60.0, -10.0, 10.0);
  FeatureExtractor whole{FeatureParams()}, assembling{FeatureParams()}, choosing{FeatureParams()};
  for (const SegmentedCloud* cloud : {&first, &second}) {
    std::vector<ScanPoint> deskewed = cloud->points;
    for (ScanPoint& p : deskewed)
      p.x += 0.01f * p.y;  // positions moved, ranges as segmented
    FeatureSet expected, assembled;
    whole.extract(*cloud, deskewed, cloud->outliers, expected);
    FeatureSelection selection;
    choosing.select(*cloud, selection);
    assembling.assemble(selection, deskewed, cloud->outliers, assembled);
    ASSERT_FALSE(expected.less_flat->empty());
    for (const auto& [a, b] : {std::make_pair(expected.sharp, assembled.sharp),
                               std::make_pair(expected.less_sharp, assembled.less_sharp),
                               std::make_pair(expected.flat, assembled.flat),
                               std::make_pair(expected.less_flat, assembled.less_flat)}) {
      ASSERT_EQ(a->size(), b->size());
      for (std::size_t i = 0; i < a->size(); ++i) {
        EXPECT_EQ((*a)[i].getVector4fMap(), (*b)[i].getVector4fMap()) << i;
        EXPECT_EQ((*a)[i].intensity, (*b)[i].intensity) << i;
      }
    }
  }
}
