#include <gtest/gtest.h>

#include <set>

#include "adaptive_lego_loam/core/clustering/run_clustering.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;

namespace {

// 4 rows 2 deg apart, 360 columns of 1 deg: at 10 m, neighbouring columns are 0.17 m apart and
// neighbouring rows 0.35 m.
SensorParams small_sensor() {
  return test::even_sensor(4, 360, -3.0, 3.0);
}

struct Clustered {
  RangeImage image;
  ClusterLabels labels;
  int label_at(int row, int col) const { return labels.label[image.cell(row, col)]; }
};

// Points at 10 m on the given (row, col) cells.
Clustered cluster_cells(const std::vector<std::pair<int, int>>& cells, double range = 10.0) {
  const SensorParams sensor = small_sensor();
  Scan scan;
  scan.has_ring = true;
  for (const auto& [row, col] : cells)
    scan.points.push_back(test::cell_point(sensor, row, col, range));
  Clustered out;
  RangeProjector projector(sensor);
  projector.project(scan, out.image);
  RunClustering(projector.geometry(), RunClusteringParams{}).cluster(out.image, {}, out.labels);
  return out;
}

std::vector<std::pair<int, int>> row_span(int row, int first_col, int last_col) {
  std::vector<std::pair<int, int>> cells;
  for (int col = first_col; col <= last_col; ++col)
    cells.push_back({row, col});
  return cells;
}

std::vector<std::pair<int, int>> joined(std::vector<std::pair<int, int>> a,
                                        const std::vector<std::pair<int, int>>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

TEST(RunClustering, GapBeyondRunThresholdSplitsARow) {
  // Columns 10-14 and 30-34 of one row: 0.17 m steps inside, a 2.8 m gap between.
  const Clustered c = cluster_cells(joined(row_span(3, 10, 14), row_span(3, 30, 34)));
  EXPECT_EQ(c.labels.clusters(), 2);
  EXPECT_EQ(c.label_at(3, 10), c.label_at(3, 14));
  EXPECT_NE(c.label_at(3, 14), c.label_at(3, 30));
  EXPECT_EQ(c.labels.size[c.label_at(3, 30)], 5);
}

TEST(RunClustering, RunsOfAdjacentRowsWithinMergeThresholdJoin) {
  // Row 2 lies 0.35 m below row 3 at 10 m: within th_merge (1 m).
  const Clustered c = cluster_cells(joined(row_span(3, 10, 14), row_span(2, 10, 14)));
  EXPECT_EQ(c.labels.clusters(), 1);
  EXPECT_EQ(c.labels.size[1], 10);
}

TEST(RunClustering, RunBelowBridgesTwoRunsAbove) {
  // Two runs in row 3 (a 1.4 m gap), one continuous run under both in row 2: one cluster.
  const Clustered c =
      cluster_cells(joined(joined(row_span(3, 10, 12), row_span(3, 20, 22)), row_span(2, 10, 22)));
  EXPECT_EQ(c.labels.clusters(), 1);
}

TEST(RunClustering, NearestPointAboveFartherThanMergeThresholdKeepsRunsApart) {
  // Row 3 at 10 m, row 2 at 12 m under it: the nearest point above is 2 m away.
  const SensorParams sensor = small_sensor();
  Scan scan;
  scan.has_ring = true;
  for (int col = 10; col <= 14; ++col) {
    scan.points.push_back(test::cell_point(sensor, 3, col, 10.0));
    scan.points.push_back(test::cell_point(sensor, 2, col, 12.0));
  }
  RangeImage image;
  RangeProjector projector(sensor);
  projector.project(scan, image);
  ClusterLabels labels;
  RunClustering(projector.geometry(), {}).cluster(image, {}, labels);
  EXPECT_EQ(labels.clusters(), 2);
}

TEST(RunClustering, MergeFindsNearestPointAboveInAnotherColumn) {
  // A single point in row 2, three columns (0.5 m) off the run above: still within th_merge.
  const Clustered c = cluster_cells(joined(row_span(3, 10, 14), {{2, 17}}));
  EXPECT_EQ(c.labels.clusters(), 1);
}

TEST(RunClustering, RowWrapsAround) {
  const Clustered c = cluster_cells(joined(row_span(1, 357, 359), row_span(1, 0, 2)));
  EXPECT_EQ(c.labels.clusters(), 1);
  EXPECT_EQ(c.labels.size[1], 6);
}

TEST(RunClustering, EmptyRowEndsTheChain) {
  // Rows 3 and 1 are 0.7 m apart, within th_merge, but only adjacent scan lines are compared.
  const Clustered c = cluster_cells(joined(row_span(3, 10, 14), row_span(1, 10, 14)));
  EXPECT_EQ(c.labels.clusters(), 2);
}

TEST(RunClustering, ExcludedCellsTakeNoPartAndSizeRuleMarksKept) {
  const SensorParams sensor = small_sensor();
  Scan scan;
  scan.has_ring = true;
  for (int col = 10; col <= 14; ++col)
    scan.points.push_back(test::cell_point(sensor, 3, col, 10.0));
  scan.points.push_back(test::cell_point(sensor, 3, 40, 10.0));
  RangeImage image;
  RangeProjector projector(sensor);
  projector.project(scan, image);
  std::vector<uint8_t> excluded(image.size(), 0);
  excluded[image.cell(3, 12)] = 1;  // cuts the run: 11 and 13 are 0.35 m apart, still joined
  ClusterLabels labels;
  RunClustering(projector.geometry(), RunClusteringParams{0.5, 1.0, 2})
      .cluster(image, excluded, labels);
  EXPECT_EQ(labels.label[image.cell(3, 12)], ClusterLabels::kNone);
  ASSERT_EQ(labels.clusters(), 2);
  EXPECT_EQ(labels.size[labels.label[image.cell(3, 10)]], 4);
  EXPECT_TRUE(labels.kept[labels.label[image.cell(3, 10)]]);
  EXPECT_FALSE(labels.kept[labels.label[image.cell(3, 40)]]);  // 1 point < min_points 2
}
