#include "adaptive_lego_loam/ros/node_diagnostics.h"

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <algorithm>
#include <cstdio>

namespace adaptive_lego_loam::ros_bridge {
namespace {

std::string number(double value, const char* format = "%.2f") {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

uint8_t to_diagnostic_level(HealthLevel level) {
  switch (level) {
    case HealthLevel::kOk:
      return diagnostic_msgs::DiagnosticStatus::OK;
    case HealthLevel::kWarn:
      return diagnostic_msgs::DiagnosticStatus::WARN;
    case HealthLevel::kError:
      return diagnostic_msgs::DiagnosticStatus::ERROR;
  }
  return diagnostic_msgs::DiagnosticStatus::ERROR;
}

}  // namespace

void HealthStatus::add(const std::string& key, double value) {
  add(key, number(value));
}

void HealthStatus::raise(HealthLevel new_level, const std::string& why) {
  level = std::max(level, new_level);
  message += (message.empty() ? "" : "; ") + why;
}

StampStep ScanHealth::received(double stamp, double now_s) {
  last_received_s_ = now_s;
  ++received_;
  return stamps_.add(stamp);
}

void ScanHealth::processed(const StageTimes& times) {
  ++processed_;
  stage_totals_.add(times);
}

void ScanHealth::dropped(const std::string& reason) {
  ++dropped_total_[reason];
  ++dropped_in_period_[reason];
}

long ScanHealth::dropped_total() const {
  long total = 0;
  for (const auto& [reason, count] : dropped_total_)
    total += count;
  return total;
}

HealthStatus ScanHealth::close_period(double now_s) {
  HealthStatus status;
  const double length = period_start_s_ ? std::max(now_s - *period_start_s_, 1e-9) : 0.0;
  const long missing = stamps_.missing() - missing_at_period_start_;
  status.add("frames per second", length > 0.0 ? processed_ / length : 0.0);
  status.add("scans received", std::to_string(received_));
  if (stage_totals_.frames() > 0) {
    const double frames = stage_totals_.frames();
    status.add("ms per scan", stage_totals_.all_ms() / frames);
    for (const auto& [stage, ms] : stage_totals_.totals_ms())
      status.add("ms " + stage, ms / frames);
  }
  status.add("scans dropped (total)", std::to_string(dropped_total()));
  for (const auto& [reason, count] : dropped_total_)
    status.add("dropped: " + reason, std::to_string(count));
  status.add("scans missing from the input (total)", std::to_string(stamps_.missing()));
  status.add("time jumps back (total)", std::to_string(stamps_.backward_jumps()));

  long dropped = 0;
  for (const auto& [reason, count] : dropped_in_period_)
    dropped += count;
  if (processed_ == 0 && (received_ > 0 || dropped > 0)) {
    // Scans came (or parts of scans that never made a whole one) and none was processed.
    status.raise(HealthLevel::kError, "every scan dropped");
  } else if (!last_received_s_) {
    status.message = "waiting for the first scan";
  } else if (now_s - *last_received_s_ > kSilenceWarning) {
    status.raise(HealthLevel::kWarn,
                 "no scan for " + number(now_s - *last_received_s_, "%.0f") + " s");
  }
  if (dropped > 0 && processed_ > 0) {
    status.raise(HealthLevel::kWarn, std::to_string(dropped) + " scans dropped");
  }
  if (missing > 0) {
    status.raise(HealthLevel::kWarn, std::to_string(missing) + " scans missing from the input");
  }
  if (stage_totals_.frames() > 0 &&
      stage_totals_.all_ms() / stage_totals_.frames() > 1000.0 * period_) {
    status.raise(HealthLevel::kWarn, "slower than the sensor");
  }
  period_start_s_ = now_s;
  received_ = processed_ = 0;
  missing_at_period_start_ = stamps_.missing();
  stage_totals_.clear();
  dropped_in_period_.clear();
  return status;
}

NodeDiagnostics::NodeDiagnostics(ros::NodeHandle& nh, ros::NodeHandle& private_nh,
                                 const std::string& node, const std::string& hardware_id,
                                 double scan_period, Extra extra)
    // The updater drops the first character of the node name (a ROS name's leading slash).
    : health_(scan_period), extra_(std::move(extra)), updater_(nh, private_nh, "/" + node) {
  updater_.setHardwareID(hardware_id);
  updater_.add("scans", this, &NodeDiagnostics::fill);
  health_.close_period(now());  // the first period starts now
  timer_ = nh.createSteadyTimer(ros::WallDuration(1.0),
                                [this](const ros::SteadyTimerEvent&) { updater_.force_update(); });
}

void NodeDiagnostics::fill(diagnostic_updater::DiagnosticStatusWrapper& status) {
  HealthStatus health = health_.close_period(now());
  if (extra_) extra_(health);
  if (health.message.empty()) health.message = "ok";
  status.summary(to_diagnostic_level(health.level), health.message);
  for (const auto& [key, value] : health.values)
    status.add(key, value);
}

}  // namespace adaptive_lego_loam::ros_bridge
