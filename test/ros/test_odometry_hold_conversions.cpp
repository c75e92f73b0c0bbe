// The odometry's follow test between the stages: the held direction crosses exactly, a bad one is
// refused with the topic named.

#include <gtest/gtest.h>

#include <limits>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/odometry_hold_conversions.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

std_msgs::Header scan_header() {
  std_msgs::Header header;
  header.stamp.fromSec(1e9 + 0.3);  // the frame plays no part
  return header;
}

TEST(OdometryHoldConversions, AHeldDirectionCrossesBitForBit) {
  OdometryResult odometry;
  odometry.held_direction = Eigen::Vector3d(0.999, 0.03, -0.01).normalized();
  odometry.follow = 0.87;
  const OdometryHold msg = odometry_hold_to_ros(odometry, scan_header());
  EXPECT_TRUE(msg.held);
  EXPECT_EQ(msg.header.stamp, scan_header().stamp);
  EXPECT_EQ(msg.follow, 0.87);
  const std::optional<Eigen::Vector3d> back = odometry_held_from_ros(msg, "/odometry_hold");
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, *odometry.held_direction);  // exact: scan-to-map holds what run_sequence holds
}

TEST(OdometryHoldConversions, AScanThatWasNotHeldGivesNoDirection) {
  OdometryResult odometry;
  odometry.follow = 0.02;
  const OdometryHold msg = odometry_hold_to_ros(odometry, scan_header());
  EXPECT_FALSE(msg.held);
  EXPECT_FALSE(odometry_held_from_ros(msg, "/odometry_hold"));
}

TEST(OdometryHoldConversions, AHeldDirectionThatIsNotAUnitVectorIsRefusedNamingTheTopic) {
  OdometryHold msg;
  msg.held = true;
  msg.direction.x = 0.5;
  try {
    odometry_held_from_ros(msg, "/odometry_hold");
    FAIL() << "a direction of length 0.5 was taken";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/odometry_hold"), std::string::npos) << e.what();
  }
  msg.direction.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(odometry_held_from_ros(msg, "/odometry_hold"), IoError);
}

}  // namespace
