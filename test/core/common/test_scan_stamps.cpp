// The stamps of a scan stream against the sensor's period: next, gap (and how many scans it
// misses), duplicate, and a jump back in time.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/core/common/scan_stamps.h"

using namespace adaptive_lego_loam;

TEST(ScanStamps, ClassifiesNextGapDuplicateAndBackward) {
  ScanStamps stamps(0.1);
  EXPECT_EQ(stamps.add(100.0), StampStep::kFirst);
  EXPECT_EQ(stamps.add(100.1), StampStep::kNext);
  EXPECT_EQ(stamps.add(100.104), StampStep::kNext) << "KITTI's periods vary by a few %";
  EXPECT_EQ(stamps.add(100.104), StampStep::kDuplicate);
  EXPECT_EQ(stamps.add(100.404), StampStep::kGap);
  EXPECT_EQ(stamps.missing(), 2) << "0.3 s is two scans missing";
  EXPECT_EQ(stamps.add(50.0), StampStep::kBackward) << "a bag played again";
  EXPECT_EQ(stamps.add(50.1), StampStep::kNext) << "and on from there";
  EXPECT_EQ(stamps.gaps(), 1);
  EXPECT_EQ(stamps.duplicates(), 1);
  EXPECT_EQ(stamps.backward_jumps(), 1);
}

TEST(ScanStamps, AGapOfMinutesCountsItsScans) {
  ScanStamps stamps(0.1);
  stamps.add(0.0);
  EXPECT_EQ(stamps.add(180.0), StampStep::kGap);
  EXPECT_EQ(stamps.missing(), 1799);
  EXPECT_NEAR(stamps.last_gap(), 180.0, 1e-9);
}

TEST(ScanStamps, ANonFiniteStampIsRejected) {
  ScanStamps stamps(0.1);
  EXPECT_THROW(stamps.add(std::nan("")), std::invalid_argument);
  EXPECT_THROW(stamps.add(INFINITY), std::invalid_argument);
}
