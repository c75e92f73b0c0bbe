#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "adaptive_lego_loam/eval/clustering_benchmark.h"
#include "adaptive_lego_loam/eval/clustering_methods.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "eval/benchmark_boxes.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

const std::string kBench = std::string(TEST_DATA_DIR) + "/clustering_bench";
const std::string kFrame = "1641652621096865";

}  // namespace

TEST(ClusteringMethods, NamesRoundTrip) {
  ASSERT_EQ(all_clustering_methods().size(), 6u);
  for (ClusteringMethod method : all_clustering_methods())
    EXPECT_EQ(method_from_name(method_name(method)), method);
  EXPECT_FALSE(method_from_name("kmeans"));
}

TEST(ClusteringMethods, EveryMethodFindsTwoDistantBoxes) {
  // Two boxes 4 m apart, each showing the sensor two faces (so its points span the whole box but
  // for the sampling), rendered by an HDL-64E-like sensor; plus one point closer than min_range,
  // which the range image drops.
  Config config;
  config.sensor = test::even_sensor(64, 1800, -24.9, 2.0);
  const AxisAlignedBox left = box(8, 2, -1.5, 10, 4, 0), right = box(8, -4, -1.5, 10, -2, 0);
  test::Scene scene;
  for (const AxisAlignedBox& b : {left, right}) {
    scene.boxes.push_back({{b.min[0], b.min[1], b.min[2]}, {b.max[0], b.max[1], b.max[2]}});
  }
  Scan scan = test::render(config.sensor, scene);
  scan.points.push_back(test::cell_point(config.sensor, 40, 10, 0.2));
  for (ClusteringMethod method : all_clustering_methods()) {
    SCOPED_TRACE(method_name(method));
    ClusteringRunner runner(method, config);
    ScanClustering result;
    runner.cluster(scan, result);
    ASSERT_EQ(result.cluster_of_point.size(), scan.points.size());
    PrecisionScore score;
    score.add_frame({object(left), object(right)},
                    cluster_boxes(scan.points, result.cluster_of_point));
    // Sampling leaves a few centimetres of each box uncovered.
    EXPECT_GT(score.precision(), 0.85);
    if (uses_range_image(method)) {
      EXPECT_EQ(result.dropped_by_projection, 1);
      EXPECT_EQ(result.unclustered_points, 1);
      EXPECT_EQ(result.cluster_of_point.back(), kUnclustered);
    }
  }
}

TEST(ClusteringMethods, MinClusterPointsDropsSmallClusters) {
  Config config;
  config.sensor = test::even_sensor(16, 360, -15, 15);
  config.clustering_benchmark.min_cluster_points = 3;
  Scan scan;
  scan.has_ring = true;
  for (int col = 100; col < 104; ++col)
    scan.points.push_back(test::cell_point(config.sensor, 8, col, 10.0));
  scan.points.push_back(test::cell_point(config.sensor, 8, 200, 10.0));  // alone
  ClusteringRunner runner(ClusteringMethod::kEuclideanKdtree, config);
  ScanClustering result;
  runner.cluster(scan, result);
  EXPECT_EQ(result.clusters, 1);
  EXPECT_EQ(result.unclustered_points, 1);
  EXPECT_EQ(result.cluster_of_point.back(), kUnclustered);
}

// One real frame of the benchmark (KITTI, ground removed, two labelled cars).
class RealBenchmarkFrame : public ::testing::Test {
 protected:
  void SetUp() override {
    config_ = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
    scan_ = read_pcd(kBench + "/points_noground/" + kFrame + ".pcd");
    objects_ = read_object_labels(kBench + "/labels/" + kFrame + ".txt");
  }
  std::vector<AxisAlignedBox> boxes_of(ClusteringMethod method, const Config& config) {
    ClusteringRunner runner(method, config);
    ScanClustering result;
    runner.cluster(scan_, result);
    return cluster_boxes(scan_.points, result.cluster_of_point);
  }
  double precision_of(ClusteringMethod method, const Config& config) {
    PrecisionScore score;
    score.add_frame(objects_, boxes_of(method, config));
    return score.precision();
  }
  Config config_;
  Scan scan_;
  std::vector<LabelledObject> objects_;
};

TEST_F(RealBenchmarkFrame, KittiBeamTableFitsThisRecording) {
  // The frames come from KITTI's object set, not sequence 07 where the table was measured: each
  // row's points must still sit on their beam (elevation seen from the beam's origin).
  RangeImage image;
  RangeProjector(config_.sensor).project(scan_, image);
  const auto& angles = config_.sensor.beam_angles_deg;
  for (int row = 0; row < image.rows(); ++row) {
    std::vector<double> residual;
    for (int col = 0; col < image.cols(); ++col) {
      const int cell = image.cell(row, col);
      if (!image.occupied(cell)) continue;
      const ScanPoint& p = image.point(cell);
      const double elevation =
          std::atan2(p.z - config_.sensor.beam_offsets_m[row], std::hypot(p.x, p.y)) * 180 / M_PI;
      residual.push_back(std::fabs(elevation - angles[row]));
    }
    if (residual.size() < 20) continue;  // too few points left by the ground removal
    std::sort(residual.begin(), residual.end());
    const double spacing = std::min(row > 0 ? angles[row] - angles[row - 1] : 180.0,
                                    row + 1 < image.rows() ? angles[row + 1] - angles[row] : 180.0);
    EXPECT_LT(residual[residual.size() * 95 / 100], 0.2 * spacing) << "row " << row;
  }
  EXPECT_EQ(image.stats().outside_rows, 0);
}

TEST_F(RealBenchmarkFrame, KdTreeEuclideanRecoversBothCars) {
  // The labelled boxes are the extents of each car's points, and both cars stand more than
  // 0.75 m from anything else: the KD-tree clustering's box is the label's box.
  ASSERT_EQ(objects_.size(), 2u);
  EXPECT_GT(precision_of(ClusteringMethod::kEuclideanKdtree, config_), 0.99);
  EXPECT_GT(precision_of(ClusteringMethod::kDbscan, config_), 0.99);
}

TEST_F(RealBenchmarkFrame, TheDistanceTestCutsCarsButNeverMergesThem) {
  // The paper's text: |AB| < gamma sin(alpha) |OB| with gamma = 1.2 is a few centimetres at these
  // cars' ranges (11 m and 28 m): far below the gap between a car and anything else, so a cluster
  // cannot reach beyond a car's box, while surfaces seen at a grazing angle are cut. Every car's
  // best cluster therefore lies inside its box, and the score is well above zero but below one.
  config_.ambient.euclidean_criterion = EuclideanCriterion::kDistance;
  config_.ambient.euclidean_window = 3;
  const std::vector<AxisAlignedBox> boxes = boxes_of(ClusteringMethod::kAdaptive, config_);
  double sum = 0.0;
  for (const LabelledObject& car : objects_) {
    const BestMatch match = best_match(car.box, boxes);
    ASSERT_GE(match.cluster, 0);
    sum += match.iou;
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GE(boxes[match.cluster].min[axis], car.box.min[axis] - 0.01);
      EXPECT_LE(boxes[match.cluster].max[axis], car.box.max[axis] + 0.01);
    }
  }
  const double precision = sum / objects_.size();
  EXPECT_GT(precision, 0.2);
  EXPECT_LT(precision, 0.9);
}

TEST_F(RealBenchmarkFrame, TheRangeDifferenceTestOfTheConfigsKeepsMoreOfEachCar) {
  // The configs' range-difference test with w 5 joins surfaces seen more obliquely and across
  // gaps of up to five cells: each car's best cluster overlaps it more than with the distance
  // test (0.62 against 0.43 here), though it may now reach a little beyond the car.
  ASSERT_EQ(config_.ambient.euclidean_criterion, EuclideanCriterion::kRangeDifference);
  ASSERT_EQ(config_.ambient.euclidean_window, 5);
  const double range_difference = precision_of(ClusteringMethod::kAdaptive, config_);
  Config distance = config_;
  distance.ambient.euclidean_criterion = EuclideanCriterion::kDistance;
  distance.ambient.euclidean_window = 3;
  const double by_distance = precision_of(ClusteringMethod::kAdaptive, distance);
  EXPECT_GT(range_difference, by_distance + 0.1) << "distance w 3: " << by_distance;
}
