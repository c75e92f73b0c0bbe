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

TEST(InputMonitor, ReportsRateAndGaps) {
  InputMonitor monitor(0.05);
  double t = 0.0;
  for (int i = 0; i < 100; ++i, t += 0.005)
    monitor.check(t, true, true);
  EXPECT_NEAR(monitor.status().rate_hz, 200.0, 1.0);
  monitor.check(t + 2.0, true, true);  // the IMU stops for 2 s and comes back
  EXPECT_EQ(monitor.status().gaps, 1);
  EXPECT_NEAR(monitor.status().latest_gap_s, 2.005, 1e-9);
  EXPECT_NEAR(monitor.status().rate_hz, 200.0, 1.0);  // a gap is not a slow sample
}

TEST(InputMonitor, CoverageLooksOnlyAtSamplesUpToTheEnd) {
  struct Sample {
    double stamp;
  };
  std::vector<Sample> samples;
  for (int i = 0; i <= 100; ++i)
    samples.push_back({0.005 * i});
  EXPECT_TRUE(samples_cover(samples, 0.2, 0.5, 0.05));
  EXPECT_FALSE(samples_cover(samples, -0.1, 0.2, 0.05));  // nothing before the start
  EXPECT_FALSE(samples_cover(samples, 0.2, 0.6, 0.05));   // nothing near the end
  samples.push_back({2.5});                               // a 2 s gap, then samples again
  EXPECT_TRUE(samples_cover(samples, 0.2, 0.5, 0.05));    // what came later changes nothing
  EXPECT_FALSE(samples_cover(samples, 0.45, 2.5, 0.05));
  for (int i = 1; i <= 20; ++i)
    samples.push_back({2.5 + 0.005 * i});
  EXPECT_TRUE(samples_cover(samples, 2.5, 2.6, 0.05));
}
