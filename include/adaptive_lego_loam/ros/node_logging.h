#pragma once
// What the nodes log besides errors: a throttle for repeated warnings and the periodic one-line
// summary of frames per second and milliseconds per stage. Both run on the steady clock, not on
// ROS time: under use_sim_time the clock may stand still (or start at 0) while scans arrive,
// and rosconsole's *_THROTTLE macros then stay silent.

#include <chrono>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adaptive_lego_loam/core/common/timing.h"

namespace adaptive_lego_loam::ros_bridge {

// Seconds on the steady clock.
double steady_seconds();

class Throttle {
 public:
  explicit Throttle(double period_s) : period_s_(period_s) {}
  // True on the first call and then at most once per period.
  bool ready() { return ready(steady_seconds()); }
  bool ready(double now_s);
  // " (N more since the last report)" after ready() returned true with N > 0 refused calls
  // before it; empty otherwise.
  std::string suppressed_note() const;

 private:
  double period_s_;
  std::optional<double> last_s_;
  int refused_ = 0;
  int refused_before_last_ = 0;
};

// A warning a node may meet on every scan, e.g. "scan dropped: ...": logged as
// "<node>: <what>" at most once a period, with how many were held back since the last one.
class ThrottledWarning {
 public:
  ThrottledWarning(std::string node, double period_s)
      : node_(std::move(node)), throttle_(period_s) {}
  void operator()(const std::string& what);

 private:
  std::string node_;
  Throttle throttle_;
};

// Each stage's milliseconds summed over the frames since the last clear().
class StageTotals {
 public:
  void add(const StageTimes& times);
  void clear();
  int frames() const { return frames_; }
  // Per stage, in first-seen order, and all stages together.
  const std::vector<std::pair<std::string, double>>& totals_ms() const { return total_ms_; }
  double all_ms() const { return all_ms_; }

 private:
  int frames_ = 0;
  std::vector<std::pair<std::string, double>> total_ms_;
  double all_ms_ = 0.0;
};

class StageSummary {
 public:
  // `label` starts the line (the node's name).
  StageSummary(std::string label, double period_s)
      : label_(std::move(label)), period_s_(period_s) {}
  // Logs what is not reported yet (INFO).
  ~StageSummary();
  StageSummary(const StageSummary&) = delete;
  StageSummary& operator=(const StageSummary&) = delete;
  // One processed frame and its stage times.
  void add(const StageTimes& times) { add(times, steady_seconds()); }
  void add(const StageTimes& times, double now_s);
  // When a period has passed since the last report (or the first frame): one line, e.g.
  // "image_projection: 9.8 frames/s over 98 frames; ms per frame: projection 3.1, ground 0.4,
  // total 7.9", and a new period starts. Nothing otherwise.
  std::optional<std::string> report() { return report(steady_seconds()); }
  std::optional<std::string> report(double now_s);
  // The same line for the frames since the last report, however short the period, with the rate
  // over the time the frames came in (at shutdown, the idle time after the last frame is not
  // the node's rate); without a rate when one frame is all there is to go by.
  std::optional<std::string> report_remaining() { return report_remaining(steady_seconds()); }
  std::optional<std::string> report_remaining(double now_s);

 private:
  std::string line(std::optional<double> frames_per_second, double now_s);
  std::string label_;
  double period_s_;
  std::optional<double> start_s_;  // the period's start: its first frame, or the last report
  bool started_at_frame_ = false;
  double last_frame_s_ = 0.0;
  StageTotals totals_;
};

// One line of a frame's stage times for the debug log: "projection 3.12 ms, ground 0.40 ms".
std::string format_stage_times(const StageTimes& times);

}  // namespace adaptive_lego_loam::ros_bridge
