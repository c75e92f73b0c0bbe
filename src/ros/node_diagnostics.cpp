#include "adaptive_lego_loam/ros/node_diagnostics.h"

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <ros/master.h>

#include <algorithm>
#include <cstdio>
#include <set>

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
  ++received_total_;
  return stamps_.add(stamp);
}

void ScanHealth::processed(const StageTimes& times) {
  ++processed_;
  ++processed_total_;
  stage_totals_.add(times);
}

void ScanHealth::dropped(const std::string& reason, const std::string& detail) {
  ++dropped_total_[reason];
  ++dropped_in_period_[reason];
  last_drop_ = detail.empty() ? reason : detail;
}

std::string ScanHealth::input_problem(double now_s) const {
  if (input_topic_.empty() || processed_total_ > 0 || !started_s_) return "";
  const double waited = now_s - *started_s_;
  if (waited < input_wait()) return "";
  if (received_total_ == 0) {
    return "no scan on " + input_topic_ + " for " + number(waited, "%.0f") + " s";
  }
  return std::to_string(received_total_) + " scans on " + input_topic_ +
         ", none usable (the last: " + last_drop_ + ")";
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
  const std::string input_problem = this->input_problem(now_s);
  if (processed_ == 0 && (received_ > 0 || dropped > 0)) {
    // Scans came (or parts of scans that never made a whole one) and none was processed.
    status.raise(HealthLevel::kError, "every scan dropped");
    if (!input_problem.empty()) status.raise(HealthLevel::kError, input_problem);
  } else if (!input_problem.empty()) {
    status.raise(HealthLevel::kWarn, input_problem);
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
  if (!started_s_) started_s_ = now_s;
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
    : node_(node),
      health_(scan_period),
      extra_(std::move(extra)),
      updater_(nh, private_nh, "/" + node) {
  updater_.setHardwareID(hardware_id);
  updater_.add("scans", this, &NodeDiagnostics::fill);
  health_.close_period(now());  // the first period starts now
  timer_ = nh.createSteadyTimer(ros::WallDuration(1.0),
                                [this](const ros::SteadyTimerEvent&) { updater_.force_update(); });
}

void NodeDiagnostics::fill(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const std::string input_problem = health_.input_problem(now());
  if (!input_problem.empty() && !input_problem_logged_) {
    input_problem_logged_ = true;
    ROS_WARN("%s", no_input_warning(node_, input_problem, published_cloud_topics()).c_str());
  }
  HealthStatus health = health_.close_period(now());
  if (extra_) extra_(health);
  if (health.message.empty()) health.message = "ok";
  status.summary(to_diagnostic_level(health.level), health.message);
  for (const auto& [key, value] : health.values)
    status.add(key, value);
}

std::string no_input_warning(const std::string& node, const std::string& problem,
                             const std::vector<std::string>& cloud_topics) {
  std::string line = node + ": " + problem + "; ";
  if (cloud_topics.empty()) {
    return line + "no PointCloud2 topic is published: is the driver running?";
  }
  line += "PointCloud2 topics published:";
  for (const std::string& topic : cloud_topics)
    line += " " + topic;
  return line + " (cloud_topic:= names the driver's)";
}

std::vector<std::string> published_cloud_topics() {
  static const std::set<std::string> own = {
      "full_cloud_projected",    "ground_cloud",         "key_pose_origin",
      "laser_cloud_corner_last", "laser_cloud_flat",     "laser_cloud_sharp",
      "laser_cloud_surf_last",   "laser_cloud_surround", "outlier_cloud",
      "outlier_cloud_last",      "segmented_cloud",      "skeleton_cloud"};
  ros::master::V_TopicInfo topics;
  std::vector<std::string> clouds;
  if (!ros::master::getTopics(topics)) return clouds;
  for (const ros::master::TopicInfo& topic : topics) {
    const std::string last = topic.name.substr(topic.name.rfind('/') + 1);
    if (topic.datatype == "sensor_msgs/PointCloud2" && !own.count(last)) {
      clouds.push_back(topic.name);
    }
  }
  std::sort(clouds.begin(), clouds.end());
  return clouds;
}

std::string direction_text(const Eigen::Vector3d& direction, double sigma_m) {
  char text[96];
  std::snprintf(text, sizeof(text), "x %.2f y %.2f z %.2f, sigma %.3g m", direction.x(),
                direction.y(), direction.z(), sigma_m);
  return text;
}

}  // namespace adaptive_lego_loam::ros_bridge
