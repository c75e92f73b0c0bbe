// The reported degenerate state: at once when a scan is degenerate, constrained again only after
// a run of clearly constrained scans; a sigma about the threshold does not toggle it.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/pipeline/degeneracy_tracker.h"

using adaptive_lego_loam::DegeneracyTracker;

TEST(DegeneracyTracker, DegenerateAtOnceConstrainedAgainAfterARunOfClearScans) {
  DegeneracyTracker tracker(0.1, 0.7, 5);
  EXPECT_FALSE(tracker.update(0.05));
  EXPECT_TRUE(tracker.update(0.3));
  for (int scan = 0; scan < 4; ++scan)
    EXPECT_TRUE(tracker.update(0.05)) << scan;
  EXPECT_FALSE(tracker.update(0.05));
  EXPECT_TRUE(tracker.update(INFINITY)) << "unknown is degenerate";
  EXPECT_TRUE(tracker.update(NAN));
}

TEST(DegeneracyTracker, ASigmaHoveringAboutTheThresholdDoesNotToggleIt) {
  DegeneracyTracker tracker(0.1, 0.7, 5);
  int changes = 0;
  bool last = false;
  for (int scan = 0; scan < 100; ++scan) {
    const double sigma = scan % 2 == 0 ? 0.105 : 0.095;  // a flag per scan toggles every scan
    const bool now = tracker.update(sigma);
    changes += now != last;
    last = now;
  }
  EXPECT_EQ(changes, 1);
  EXPECT_TRUE(tracker.degenerate());
  // Between 70 % of the threshold and the threshold the state holds either way.
  tracker.reset();
  for (int scan = 0; scan < 20; ++scan)
    EXPECT_FALSE(tracker.update(0.09));
}
