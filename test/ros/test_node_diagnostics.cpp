// What a node reports on /diagnostics over each period: the level (OK, WARN, ERROR) and its
// reason, frames per second and the counts, on the steady clock (ScanHealth, without ROS).

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "adaptive_lego_loam/ros/node_diagnostics.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

std::map<std::string, std::string> values_of(const HealthStatus& status) {
  std::map<std::string, std::string> values;
  for (const auto& [key, value] : status.values)
    values[key] = value;
  return values;
}

StageTimes times_of(double ms) {
  StageTimes times;
  times.add("mapping", ms);
  return times;
}

}  // namespace

TEST(ScanHealth, OkWhileWaitingAndWhileEveryScanIsProcessedInTime) {
  ScanHealth health(0.1);
  EXPECT_EQ(health.close_period(0.0).level, HealthLevel::kOk);
  EXPECT_EQ(health.close_period(1.0).message, "waiting for the first scan");
  for (int i = 0; i < 10; ++i) {
    health.received(100.0 + 0.1 * i, 1.0 + 0.1 * i);
    health.processed(times_of(20.0));
  }
  const HealthStatus status = health.close_period(2.0);
  EXPECT_EQ(status.level, HealthLevel::kOk) << status.message;
  const auto values = values_of(status);
  EXPECT_EQ(values.at("frames per second"), "10.00");
  EXPECT_EQ(values.at("ms mapping"), "20.00");
  EXPECT_EQ(values.at("scans dropped (total)"), "0");
}

TEST(ScanHealth, DroppedAndMissingScansWarnWithTheirReason) {
  ScanHealth health(0.1);
  health.close_period(0.0);
  health.received(100.0, 0.1);
  health.processed(times_of(20.0));
  health.received(100.5, 0.2);  // four scans missing: the driver fell behind
  health.processed(times_of(20.0));
  health.received(100.6, 0.3);
  health.dropped("bad cloud");
  const HealthStatus status = health.close_period(1.0);
  EXPECT_EQ(status.level, HealthLevel::kWarn);
  EXPECT_NE(status.message.find("1 scans dropped"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("4 scans missing"), std::string::npos) << status.message;
  const auto values = values_of(status);
  EXPECT_EQ(values.at("dropped: bad cloud"), "1");
  EXPECT_EQ(values.at("scans missing from the input (total)"), "4");
  // The next period without trouble is OK again; the totals stay.
  health.received(100.7, 1.1);
  health.processed(times_of(20.0));
  const HealthStatus next = health.close_period(2.0);
  EXPECT_EQ(next.level, HealthLevel::kOk) << next.message;
  EXPECT_EQ(values_of(next).at("scans dropped (total)"), "1");
}

TEST(ScanHealth, ErrorWhenScansOrTheirPartsCameAndNoneWasProcessed) {
  ScanHealth bad_clouds(0.1);
  bad_clouds.close_period(0.0);
  for (int i = 0; i < 5; ++i) {
    bad_clouds.received(100.0 + 0.1 * i, 0.1 * i);
    bad_clouds.dropped("bad cloud");
  }
  EXPECT_EQ(bad_clouds.close_period(1.0).level, HealthLevel::kError);
  // A downstream node whose inputs never pair into a whole scan receives none at all.
  ScanHealth unpaired(0.1);
  unpaired.close_period(0.0);
  unpaired.dropped("incomplete group");
  const HealthStatus status = unpaired.close_period(1.0);
  EXPECT_EQ(status.level, HealthLevel::kError);
  EXPECT_EQ(status.message, "every scan dropped");
}

TEST(ScanHealth, SilenceAfterTheFirstScanAndASlowStageWarn) {
  ScanHealth health(0.1);
  health.close_period(0.0);
  health.received(100.0, 0.5);
  health.processed(times_of(150.0));  // slower than the 100 ms period
  const HealthStatus slow = health.close_period(1.0);
  EXPECT_EQ(slow.level, HealthLevel::kWarn);
  EXPECT_NE(slow.message.find("slower than the sensor"), std::string::npos) << slow.message;
  const HealthStatus silent = health.close_period(4.0);
  EXPECT_EQ(silent.level, HealthLevel::kWarn);
  EXPECT_NE(silent.message.find("no scan for 4 s"), std::string::npos) << silent.message;
}

// A node started on the wrong topic (or before its driver) says so after five sensor periods
// (at least a second): a warning naming the topic, not "waiting" at level OK however long.
TEST(ScanHealth, AWatchedInputThatStaysSilentWarnsNamingTheTopic) {
  ScanHealth health(0.1);
  health.watch_input("/velodyne_points");
  health.close_period(0.0);
  EXPECT_EQ(health.input_problem(0.9), "");
  EXPECT_EQ(health.close_period(0.9).level, HealthLevel::kOk);
  EXPECT_EQ(health.input_problem(3.0), "no scan on /velodyne_points for 3 s");
  const HealthStatus status = health.close_period(3.0);
  EXPECT_EQ(status.level, HealthLevel::kWarn);
  EXPECT_EQ(status.message, "no scan on /velodyne_points for 3 s");
  // At 2 Hz the wait is five periods.
  ScanHealth slow(0.5);
  slow.watch_input("/points");
  slow.close_period(0.0);
  EXPECT_EQ(slow.input_problem(2.0), "");
  EXPECT_NE(slow.input_problem(2.6), "");
}

TEST(ScanHealth, CloudsThatCannotBeUsedAreAnInputProblemToo) {
  ScanHealth health(0.1);
  health.watch_input("/ouster/points");
  health.close_period(0.0);
  for (int i = 0; i < 12; ++i) {
    health.received(100.0 + 0.1 * i, 0.1 * i);
    health.dropped("bad cloud", "/ouster/points: no valid point among 65536: 65536 out of range");
  }
  const std::string problem = health.input_problem(1.5);
  EXPECT_EQ(problem,
            "12 scans on /ouster/points, none usable (the last: /ouster/points: no valid point "
            "among 65536: 65536 out of range)");
  const HealthStatus status = health.close_period(1.5);
  EXPECT_EQ(status.level, HealthLevel::kError);
  EXPECT_NE(status.message.find(problem), std::string::npos) << status.message;
  // One scan used and the input is fine, whatever comes after.
  health.received(102.0, 2.0);
  health.processed(times_of(20.0));
  EXPECT_EQ(health.input_problem(10.0), "");
}

TEST(ScanHealth, AnUnwatchedInputWaitsAtLevelOk) {
  ScanHealth health(0.1);
  health.close_period(0.0);
  const HealthStatus status = health.close_period(30.0);
  EXPECT_EQ(status.level, HealthLevel::kOk);
  EXPECT_EQ(status.message, "waiting for the first scan");
}

TEST(NoInputWarning, NamesTheCloudTopicsThatExistOrTheirAbsence) {
  EXPECT_EQ(no_input_warning("image_projection", "no scan on /velodyne_points for 2 s",
                             {"/ouster/points", "/rslidar_points"}),
            "image_projection: no scan on /velodyne_points for 2 s; PointCloud2 topics published: "
            "/ouster/points /rslidar_points (cloud_topic:= names the driver's)");
  EXPECT_EQ(no_input_warning("image_projection", "no scan on /velodyne_points for 2 s", {}),
            "image_projection: no scan on /velodyne_points for 2 s; no PointCloud2 topic is "
            "published: is the driver running?");
}

// Both nodes' weakest-direction lines read the same; an unknown sigma says so.
TEST(DirectionText, TheDirectionAndItsSigmaInMetres) {
  EXPECT_EQ(direction_text(Eigen::Vector3d(0.99, 0.05, 0.0), 0.312),
            "x 0.99 y 0.05 z 0.00, sigma 0.312 m");
  EXPECT_EQ(direction_text(Eigen::Vector3d::UnitX(), INFINITY),
            "x 1.00 y 0.00 z 0.00, sigma inf m");
}
