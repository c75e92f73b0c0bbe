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
