#include <gtest/gtest.h>

#include <std_msgs/Int32.h>

#include <boost/make_shared.hpp>

#include "adaptive_lego_loam/ros/stamp_matcher.h"

using namespace adaptive_lego_loam::ros_bridge;

namespace {

StampMatcher::Message message(int value) {
  auto msg = boost::make_shared<std_msgs::Int32>();
  msg->data = value;
  return msg;
}

ros::Time at(double seconds) {
  return ros::Time(seconds);
}

int value(const StampMatcher::Group& group, std::size_t slot) {
  return group.get<std_msgs::Int32>(slot)->data;
}

}  // namespace

TEST(StampMatcher, CompletesAGroupWhateverTheOrder) {
  StampMatcher matcher({"cloud", "info", "outliers"}, 10);
  EXPECT_FALSE(matcher.add(2, at(1.0), message(12)));
  EXPECT_FALSE(matcher.add(0, at(1.0), message(10)));
  const auto group = matcher.add(1, at(1.0), message(11));
  ASSERT_TRUE(group);
  EXPECT_EQ(group->stamp, at(1.0));
  EXPECT_EQ(value(*group, 0), 10);
  EXPECT_EQ(value(*group, 1), 11);
  EXPECT_EQ(value(*group, 2), 12);
  EXPECT_EQ(matcher.pending(), 0u);
  EXPECT_TRUE(matcher.take_dropped().empty());
}

TEST(StampMatcher, InterleavedScansPairByStamp) {
  StampMatcher matcher({"a", "b"}, 10);
  EXPECT_FALSE(matcher.add(0, at(1.0), message(1)));
  EXPECT_FALSE(matcher.add(0, at(1.1), message(2)));
  const auto first = matcher.add(1, at(1.0), message(3));
  ASSERT_TRUE(first);
  EXPECT_EQ(value(*first, 0), 1);
  const auto second = matcher.add(1, at(1.1), message(4));
  ASSERT_TRUE(second);
  EXPECT_EQ(value(*second, 0), 2);
  EXPECT_TRUE(matcher.take_dropped().empty());
}

TEST(StampMatcher, PartialGroupOlderThanACompleteOneIsDroppedNamingWhatIsMissing) {
  StampMatcher matcher({"cloud", "info", "outliers"}, 10);
  matcher.add(0, at(1.0), message(1));  // its info and outliers never come
  matcher.add(0, at(1.1), message(2));
  matcher.add(1, at(1.1), message(3));
  EXPECT_TRUE(matcher.add(2, at(1.1), message(4)));
  const auto dropped = matcher.take_dropped();
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].stamp, at(1.0));
  EXPECT_EQ(dropped[0].missing, (std::vector<std::string>{"info", "outliers"}));
  EXPECT_EQ(dropped[0].describe(), "scan at 1.000 s dropped: no info, outliers for it");
  EXPECT_TRUE(matcher.take_dropped().empty()) << "reported once";
  EXPECT_EQ(matcher.pending(), 0u);
}

TEST(StampMatcher, LateMessageIsDroppedAtOnce) {
  StampMatcher matcher({"a", "b"}, 10);
  matcher.add(0, at(2.0), message(1));
  ASSERT_TRUE(matcher.add(1, at(2.0), message(2)));
  EXPECT_FALSE(matcher.add(0, at(1.0), message(3)));
  EXPECT_FALSE(matcher.add(1, at(2.0), message(4)));  // a second copy of a completed stamp
  const auto dropped = matcher.take_dropped();
  ASSERT_EQ(dropped.size(), 2u);
  EXPECT_TRUE(dropped[0].late);
  EXPECT_NE(dropped[0].describe().find("after a later scan"), std::string::npos);
  EXPECT_EQ(matcher.pending(), 0u);
}

TEST(StampMatcher, TooManyPendingDropsTheOldest) {
  StampMatcher matcher({"a", "b"}, 2);
  matcher.add(0, at(1.0), message(1));
  matcher.add(0, at(1.1), message(2));
  EXPECT_TRUE(matcher.take_dropped().empty());
  matcher.add(0, at(1.2), message(3));
  const auto dropped = matcher.take_dropped();
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].stamp, at(1.0));
  EXPECT_EQ(dropped[0].missing, std::vector<std::string>{"b"});
  EXPECT_EQ(matcher.pending(), 2u);
  EXPECT_TRUE(matcher.add(1, at(1.1), message(4)));
}

TEST(StampMatcher, SecondMessageOfASlotReplacesTheFirst) {
  StampMatcher matcher({"a", "b"}, 10);
  matcher.add(0, at(1.0), message(1));
  matcher.add(0, at(1.0), message(2));
  const auto group = matcher.add(1, at(1.0), message(3));
  ASSERT_TRUE(group);
  EXPECT_EQ(value(*group, 0), 2);
}

TEST(StampMatcher, RejectsBadConstructionAndSlots) {
  EXPECT_THROW(StampMatcher({}, 1), std::invalid_argument);
  EXPECT_THROW(StampMatcher({"a"}, 0), std::invalid_argument);
  StampMatcher matcher({"a"}, 1);
  EXPECT_THROW(matcher.add(1, at(1.0), message(1)), std::out_of_range);
  EXPECT_TRUE(matcher.add(0, at(1.0), message(1))) << "one slot completes at once";
}
