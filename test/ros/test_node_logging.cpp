#include <gtest/gtest.h>

#include "adaptive_lego_loam/ros/node_logging.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

TEST(Throttle, FirstCallPassesThenOncePerPeriodCountingTheRefused) {
  Throttle throttle(5.0);
  EXPECT_TRUE(throttle.ready(100.0));
  EXPECT_EQ(throttle.suppressed_note(), "");
  EXPECT_FALSE(throttle.ready(101.0));
  EXPECT_FALSE(throttle.ready(104.9));
  EXPECT_TRUE(throttle.ready(105.0));
  EXPECT_EQ(throttle.suppressed_note(), " (2 more since the last report)");
  EXPECT_TRUE(throttle.ready(111.0));
  EXPECT_EQ(throttle.suppressed_note(), "");
}

TEST(Throttle, ZeroPeriodPassesEverything) {
  Throttle throttle(0.0);
  EXPECT_TRUE(throttle.ready(1.0));
  EXPECT_TRUE(throttle.ready(1.0));
}

TEST(StageSummary, ReportsRateAndMeanMillisecondsOncePerPeriod) {
  StageSummary summary("image_projection", 10.0);
  StageTimes times;
  times.add("projection", 3.0);
  times.add("ground", 1.0);
  summary.add(times, 0.0);
  EXPECT_FALSE(summary.report(5.0));
  StageTimes slower;
  slower.add("projection", 5.0);
  slower.add("ground", 1.0);
  slower.add("extra", 2.0);
  summary.add(slower, 5.0);
  const auto line = summary.report(10.0);
  ASSERT_TRUE(line);
  EXPECT_EQ(*line,
            "image_projection: 0.2 frames/s over 2 frames; ms per frame: projection 4.0, "
            "ground 1.0, extra 1.0, total 6.0");
  EXPECT_FALSE(summary.report(30.0)) << "no frame since the last report";
  summary.add(times, 30.0);
  const auto next = summary.report(30.0);
  ASSERT_TRUE(next);
  EXPECT_NE(next->find("over 1 frames"), std::string::npos) << *next;
}

TEST(StageSummary, AShortRunStillGetsItsLine) {
  StageSummary summary("map_optimization", 10.0);
  EXPECT_FALSE(summary.report_remaining(0.0)) << "nothing to say before any frame";
  StageTimes times;
  times.add("mapping", 4.0);
  for (int frame = 0; frame < 5; ++frame)
    summary.add(times, 0.1 * frame);
  EXPECT_FALSE(summary.report(0.5)) << "the period has not passed";
  // Shut down 30 s after the bag's last scan: the rate is the one the scans came in at.
  const auto line = summary.report_remaining(30.4);
  ASSERT_TRUE(line);
  EXPECT_EQ(*line,
            "map_optimization: 10.0 frames/s over 5 frames; ms per frame: mapping 4.0, "
            "total 4.0");
  EXPECT_FALSE(summary.report_remaining(30.5)) << "reported once";
}

TEST(StageSummary, TheRestAfterAReportCountsFromTheReport) {
  StageSummary summary("image_projection", 10.0);
  StageTimes times;
  times.add("projection", 3.0);
  summary.add(times, 0.0);
  summary.add(times, 5.0);
  ASSERT_TRUE(summary.report(10.0));
  summary.add(times, 10.5);
  summary.add(times, 11.0);
  const auto line = summary.report_remaining(60.0);
  ASSERT_TRUE(line);
  EXPECT_NE(line->find(": 2.0 frames/s over 2 frames"), std::string::npos) << *line;
}

TEST(StageSummary, OneFrameAloneHasNoRate) {
  StageSummary summary("transform_fusion", 10.0);
  StageTimes times;
  times.add("fusion", 0.2);
  summary.add(times, 3.0);
  const auto line = summary.report_remaining(9.0);
  ASSERT_TRUE(line);
  EXPECT_EQ(*line, "transform_fusion: 1 frames; ms per frame: fusion 0.2, total 0.2");
}

TEST(StageSummary, FormatsOneFrame) {
  StageTimes times;
  times.add("deskew", 0.126);
  times.add("features", 2.5);
  EXPECT_EQ(format_stage_times(times), "deskew 0.13 ms, features 2.50 ms");
}
