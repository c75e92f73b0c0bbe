#pragma once
// The ego vehicle's speed over time on a synthetic path: a cruise speed that varies slowly, plus
// smooth changes of speed (braking, stopping, pulling away). Acceleration stays continuous and
// jerk bounded, so that an IMU derived from the trajectory sees no impulses.

#include <vector>

namespace adaptive_lego_loam::sim {

// A change of speed by `delta_mps` that starts at `start_time_s`: the acceleration rises from 0
// to +-`acceleration_mps2` over `ramp_s` (half a cosine), holds, and falls back to 0 over
// `ramp_s`. Jerk stays below pi / 2 * acceleration / ramp. A change smaller than acceleration x
// ramp never reaches the full acceleration (it peaks at |delta| / ramp).
struct SpeedChange {
  double start_time_s = 0.0;
  double delta_mps = 0.0;
  double acceleration_mps2 = 1.0;  // > 0
  double ramp_s = 1.0;             // > 0

  double duration() const;
  double end_time() const { return start_time_s + duration(); }
  // The change's share of the speed, acceleration and distance at `time` (0 before it starts;
  // the distance integrates from the start of the drive, time 0, on).
  double speed(double time) const;
  double acceleration(double time) const;
  double distance(double time) const;
};

// v(t) = v0 (1 + a sin(2 pi t / T + phase)) + the changes.
struct SpeedProfile {
  double cruise_mps = 10.0;
  double variation = 0.1;  // a
  double period_s = 20.0;  // T
  double phase = 0.0;
  std::vector<SpeedChange> changes;

  double speed(double time) const;
  double acceleration(double time) const;
  double distance(double time) const;  // integral of v from 0 to time
  // The first time at or after `from` by which the drive has covered `distance` m; the drive
  // must reach it (its speed positive in the end).
  double time_at_distance(double distance, double from = 0.0) const;
};

}  // namespace adaptive_lego_loam::sim
