#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/range_image.h"
#include "adaptive_lego_loam/eval/clustering_benchmark.h"
#include "adaptive_lego_loam/eval/clustering_methods.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "synthetic.h"

using namespace adaptive_lego_loam;

namespace {

const std::string kBench = std::string(TEST_DATA_DIR) + "/clustering_bench";
const std::string kFrame = "1641652621096865";

AxisAlignedBox box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {{x0, y0, z0}, {x1, y1, z1}};
}

ScanPoint at(double x, double y, double z) {
  ScanPoint p;
  p.x = static_cast<float>(x);
  p.y = static_cast<float>(y);
  p.z = static_cast<float>(z);
  return p;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string error_reading(const std::string& path) {
  try {
    read_object_labels(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

LabelledObject object(const AxisAlignedBox& b) {
  return {"car", b};
}

}  // namespace

TEST(Iou3d, IdenticalDisjointAndPartialBoxes) {
  const AxisAlignedBox unit = box(0, 0, 0, 1, 1, 1);
  EXPECT_DOUBLE_EQ(iou_3d(unit, unit), 1.0);
  EXPECT_DOUBLE_EQ(iou_3d(unit, box(2, 0, 0, 3, 1, 1)), 0.0);
  EXPECT_DOUBLE_EQ(iou_3d(unit, box(1, 0, 0, 2, 1, 1)), 0.0);  // touching faces
  // Half of each overlaps: intersection 0.5, union 1.5.
  EXPECT_DOUBLE_EQ(iou_3d(unit, box(0.5, 0, 0, 1.5, 1, 1)), 1.0 / 3.0);
  // A box inside another: the ratio of volumes.
  EXPECT_DOUBLE_EQ(iou_3d(box(0, 0, 0, 2, 2, 2), unit), 1.0 / 8.0);
  EXPECT_DOUBLE_EQ(iou_3d(unit, box(0.5, 0.5, 0.5, 0.5, 0.5, 0.5)), 0.0);  // a single point
}

TEST(ClusterBoxes, SpanTheirPointsAndSkipUnclustered) {
  const std::vector<ScanPoint> points = {at(0, 0, 0), at(1, 2, 3), at(5, 5, 5), at(-4, 0, 0),
                                         at(6, 4, 7)};
  const std::vector<AxisAlignedBox> boxes =
      cluster_boxes(points, {0, 0, 2, kUnclustered, 2});  // id 1 unused: no box
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].min, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(boxes[0].max, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(boxes[1].min, (std::array<double, 3>{5, 4, 5}));
  EXPECT_EQ(boxes[1].max, (std::array<double, 3>{6, 5, 7}));
  EXPECT_THROW(cluster_boxes(points, {0, 1}), std::invalid_argument);
}

TEST(Precision, ExactClustersScoreOneAndAMergedPairLess) {
  // Two unit boxes 1 m apart, each with points on two opposite corners.
  const std::vector<LabelledObject> objects = {object(box(0, 0, 0, 1, 1, 1)),
                                               object(box(2, 0, 0, 3, 1, 1))};
  const std::vector<ScanPoint> points = {at(0, 0, 0), at(1, 1, 1), at(2, 0, 0), at(3, 1, 1)};

  PrecisionScore separate;
  separate.add_frame(objects, cluster_boxes(points, {0, 0, 1, 1}));
  EXPECT_DOUBLE_EQ(separate.precision(), 1.0);

  // One cluster over both: its box [0, 3] x [0, 1] x [0, 1] holds each object a third.
  PrecisionScore merged;
  merged.add_frame(objects, cluster_boxes(points, {0, 0, 0, 0}));
  EXPECT_DOUBLE_EQ(merged.precision(), 1.0 / 3.0);
  EXPECT_EQ(merged.objects(), 2);
}

TEST(Precision, IsTheMeanOverAllBoxesOfAllFrames) {
  PrecisionScore score;
  score.add_frame({object(box(0, 0, 0, 1, 1, 1)), object(box(5, 0, 0, 6, 1, 1))},
                  {box(0, 0, 0, 1, 1, 1), box(5, 0, 0, 6, 1, 1), box(9, 9, 9, 10, 10, 10)});
  score.add_frame({object(box(0, 0, 0, 1, 1, 1))}, {});  // no cluster: scores 0
  EXPECT_EQ(score.frames(), 2);
  EXPECT_EQ(score.objects(), 3);
  EXPECT_DOUBLE_EQ(score.precision(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(PrecisionScore().precision(), 0.0);
}

TEST(BestMatch, PicksTheHighestIou) {
  const BestMatch match = best_match(
      box(0, 0, 0, 1, 1, 1), {box(5, 5, 5, 6, 6, 6), box(0, 0, 0, 2, 1, 1), box(0, 0, 0, 1, 1, 1)});
  EXPECT_EQ(match.cluster, 2);
  EXPECT_DOUBLE_EQ(match.iou, 1.0);
  EXPECT_EQ(best_match(box(0, 0, 0, 1, 1, 1), {box(5, 5, 5, 6, 6, 6)}).cluster, -1);
}

TEST(ObjectLabels, ReadsTheBenchmarkFormat) {
  const std::string path =
      write_temp("labels_ok.txt",
                 "car 25.3 4.8 -1.0 25.148 4.279 -1.578 25.589 5.48 -0.625 0\n\n"
                 "pedestrian 3.9 4.6 -1.3 2.5 4.269 -1.853 6.436 5.997 -0.374 1\r\n");
  const std::vector<LabelledObject> objects = read_object_labels(path);
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].object_class, "car");
  EXPECT_DOUBLE_EQ(objects[0].box.min[0], 25.148);
  EXPECT_DOUBLE_EQ(objects[0].box.max[2], -0.625);
  EXPECT_EQ(objects[1].object_class, "pedestrian");
  EXPECT_DOUBLE_EQ(objects[1].box.min[1], 4.269);
}

TEST(ObjectLabels, MalformedLineNamesFileAndLine) {
  const std::string good = "car 1 2 3 0 0 0 1 1 1 0\n";
  const std::string short_line =
      write_temp("labels_short.txt", good + good + "car 1 2 3 0 0 0 1\n");
  std::string error = error_reading(short_line);
  EXPECT_NE(error.find(short_line + ":3"), std::string::npos) << error;
  EXPECT_NE(error.find("class cx cy cz"), std::string::npos) << error;

  const std::string word = write_temp("labels_word.txt", "car 1 2 3 0 0 zero 1 1 1 0\n");
  EXPECT_NE(error_reading(word).find(word + ":1"), std::string::npos);
  const std::string extra = write_temp("labels_extra.txt", good + "car 1 2 3 0 0 0 1 1 1 0 7\n");
  EXPECT_NE(error_reading(extra).find(extra + ":2"), std::string::npos);
  const std::string inverted = write_temp("labels_inverted.txt", "car 1 2 3 2 0 0 1 1 1 0\n");
  error = error_reading(inverted);
  EXPECT_NE(error.find(inverted + ":1"), std::string::npos) << error;
  EXPECT_NE(error.find("min <= max"), std::string::npos) << error;
  EXPECT_NE(error_reading("/nonexistent/labels.txt").find("/nonexistent/labels.txt"),
            std::string::npos);
}

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

TEST_F(RealBenchmarkFrame, AdaptiveClusteringCutsCarsButNeverMergesThem) {
  // |AB| < gamma sin(alpha) |OB| with gamma = 1.2 is a few centimetres at these cars' ranges
  // (11 m and 28 m): far below the gap between a car and anything else, so a cluster cannot
  // reach beyond a car's box, while surfaces seen at a grazing angle are cut. Every car's best
  // cluster therefore lies inside its box, and the score is well above zero but below one.
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
