#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/motion_sensors/input_monitor.h"

using namespace adaptive_lego_loam;

TEST(InputMonitor, CountsEachFaultAndDropsIt) {
  InputMonitor monitor(0.05);
  EXPECT_FALSE(monitor.check(1.00, true, true));
  EXPECT_EQ(monitor.check(1.01, false, true), SampleFault::kNotFinite);
  EXPECT_EQ(monitor.check(0.99, true, true), SampleFault::kOutOfOrder);
  EXPECT_EQ(monitor.check(1.00, true, true), SampleFault::kRepeatedStamp);
  EXPECT_EQ(monitor.check(1.02, true, false), SampleFault::kBeyondLimits);
  EXPECT_FALSE(monitor.check(1.005, true, true));
  const InputStatus& status = monitor.status();
  EXPECT_EQ(status.accepted, 2);
  EXPECT_EQ(status.dropped(), 4);
  for (long count : status.faults)
    EXPECT_EQ(count, 1);
  EXPECT_STREQ(to_string(SampleFault::kOutOfOrder), "out of order");
}

TEST(InputMonitor, ReportsRateAndGapsAndCoverage) {
  InputMonitor monitor(0.05);
  double t = 0.0;
  for (int i = 0; i < 100; ++i, t += 0.005)
    monitor.check(t, true, true);
  EXPECT_NEAR(monitor.status().rate_hz, 200.0, 1.0);
  EXPECT_TRUE(monitor.covers(0.2, 0.5));
  monitor.check(t + 2.0, true, true);  // the IMU stops for 2 s and comes back
  EXPECT_EQ(monitor.status().gaps, 1);
  EXPECT_NEAR(monitor.status().latest_gap_s, 2.005, 1e-9);
  EXPECT_FALSE(monitor.covers(t, t + 2.0));
  EXPECT_NEAR(monitor.status().rate_hz, 200.0, 1.0);  // a gap is not a slow sample
  // Covered again once the interval starts after the gap.
  for (int i = 1; i <= 40; ++i)
    monitor.check(t + 2.0 + 0.005 * i, true, true);
  EXPECT_TRUE(monitor.covers(t + 2.05, t + 2.2));
}
