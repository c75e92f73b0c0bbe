#include "adaptive_lego_loam/ros/node_logging.h"

#include <ros/console.h>

#include <algorithm>
#include <cstdio>

namespace adaptive_lego_loam::ros_bridge {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool Throttle::ready(double now_s) {
  if (last_s_ && now_s - *last_s_ < period_s_) {
    ++refused_;
    return false;
  }
  last_s_ = now_s;
  refused_before_last_ = refused_;
  refused_ = 0;
  return true;
}

std::string Throttle::suppressed_note() const {
  if (refused_before_last_ == 0) return "";
  return " (" + std::to_string(refused_before_last_) + " more since the last report)";
}

void ThrottledWarning::operator()(const std::string& what) {
  if (throttle_.ready()) {
    ROS_WARN("%s: %s%s", node_.c_str(), what.c_str(), throttle_.suppressed_note().c_str());
  }
}

void StageTotals::add(const StageTimes& times) {
  ++frames_;
  for (const auto& [stage, ms] : times.entries()) {
    auto it = total_ms_.begin();
    while (it != total_ms_.end() && it->first != stage)
      ++it;
    if (it == total_ms_.end()) {
      total_ms_.emplace_back(stage, ms);
    } else {
      it->second += ms;
    }
  }
  all_ms_ += times.total();
}

void StageTotals::clear() {
  frames_ = 0;
  total_ms_.clear();
  all_ms_ = 0.0;
}

void StageSummary::add(const StageTimes& times, double now_s) {
  if (!start_s_) {
    start_s_ = now_s;
    started_at_frame_ = true;
  }
  last_frame_s_ = now_s;
  totals_.add(times);
}

StageSummary::~StageSummary() {
  // A short run (a bag of a few scans) ends before the first period: say what it did.
  if (const auto line = report_remaining()) ROS_INFO("%s", line->c_str());
}

std::optional<std::string> StageSummary::report(double now_s) {
  if (!start_s_ || totals_.frames() == 0 || now_s - *start_s_ < period_s_) return std::nullopt;
  return line(totals_.frames() / std::max(now_s - *start_s_, 1e-9), now_s);
}

std::optional<std::string> StageSummary::report_remaining(double now_s) {
  if (!start_s_ || totals_.frames() == 0) return std::nullopt;
  // A period that began with a frame holds one interval fewer than frames.
  const int intervals = totals_.frames() - (started_at_frame_ ? 1 : 0);
  const double span_s = last_frame_s_ - *start_s_;
  std::optional<double> rate;
  if (intervals > 0 && span_s > 0.0) rate = intervals / span_s;
  return line(rate, now_s);
}

std::string StageSummary::line(std::optional<double> frames_per_second, double now_s) {
  const int frames = totals_.frames();
  char number[64];
  std::string line = label_ + ": ";
  if (frames_per_second) {
    std::snprintf(number, sizeof(number), "%.1f", *frames_per_second);
    line += std::string(number) + " frames/s over ";
  }
  line += std::to_string(frames) + " frames; ms per frame:";
  for (const auto& [stage, ms] : totals_.totals_ms()) {
    std::snprintf(number, sizeof(number), " %.1f", ms / frames);
    line += " " + stage + number + ",";
  }
  std::snprintf(number, sizeof(number), " %.1f", totals_.all_ms() / frames);
  line += std::string(" total") + number;
  start_s_ = now_s;
  started_at_frame_ = false;
  totals_.clear();
  return line;
}

std::string format_stage_times(const StageTimes& times) {
  std::string line;
  char number[32];
  for (const auto& [stage, ms] : times.entries()) {
    std::snprintf(number, sizeof(number), " %.2f ms", ms);
    line += (line.empty() ? "" : ", ") + stage + number;
  }
  return line;
}

}  // namespace adaptive_lego_loam::ros_bridge
