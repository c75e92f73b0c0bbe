#pragma once
// What a node publishes on /diagnostics (diagnostic_msgs/DiagnosticArray, diagnostic_updater)
// once a second on the steady clock: frames per second, milliseconds per stage, scans dropped by
// reason, scans missing from its input (gaps in the stamps against the sensor period: the driver
// or an earlier stage fell behind, or a queue overflowed), and the node's own values.
//
// Levels, over the last period:
//   ERROR  scans (or parts of scans) arrived but none was processed, or the node says so
//          (localization lost);
//   WARN   scans were dropped or went missing, the mean frame took longer than the sensor period,
//          or no scan came for 2 s after the first; for a node watching its input (the driver's
//          clouds), no scan, or none it could use, since it started a few sensor periods ago;
//   OK     otherwise (also before the first scan).

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <Eigen/Core>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adaptive_lego_loam/core/common/scan_stamps.h"
#include "adaptive_lego_loam/ros/node_logging.h"

namespace adaptive_lego_loam::ros_bridge {

enum class HealthLevel { kOk = 0, kWarn = 1, kError = 2 };

struct HealthStatus {
  HealthLevel level = HealthLevel::kOk;
  std::string message;                                      // what is wrong; empty when nothing is
  std::vector<std::pair<std::string, std::string>> values;  // key, value, in display order

  void add(const std::string& key, const std::string& value) { values.emplace_back(key, value); }
  void add(const std::string& key, double value);
  // Raises the level to `level` (never lowers it) and appends `why` to the message.
  void raise(HealthLevel level, const std::string& why);
};

// The counts behind a node's status, on seconds of the steady clock (unit-testable without ROS).
class ScanHealth {
 public:
  static constexpr double kSilenceWarning = 2.0;  // s without a scan after the first

  explicit ScanHealth(double scan_period) : period_(scan_period), stamps_(scan_period) {}
  // A scan arrived with this stamp (s); returns how its stamp follows the last one.
  StampStep received(double stamp, double now_s);
  void processed(const StageTimes& times);
  // `detail`: why, as logged (the input's problem names the last).
  void dropped(const std::string& reason, const std::string& detail = "");

  // Watches the input `topic`: once no scan has been used since the first period started, for
  // five sensor periods and at least a second, input_problem() says so and the status warns.
  void watch_input(const std::string& topic) { input_topic_ = topic; }
  // "no scan on T for N s" or "N scans on T, none usable (the last: ...)"; empty once a scan was
  // used, before the wait is over, or when the input is not watched.
  std::string input_problem(double now_s) const;
  double input_wait() const { return std::max(5.0 * period_, 1.0); }
  // The status of the period since the last call; a new period starts.
  HealthStatus close_period(double now_s);

  long dropped_total() const;
  const std::map<std::string, long>& dropped_by_reason() const { return dropped_total_; }
  long missing_total() const { return stamps_.missing(); }

 private:
  double period_;
  ScanStamps stamps_;
  std::optional<double> last_received_s_, period_start_s_, started_s_;
  int received_ = 0, processed_ = 0;
  long received_total_ = 0, processed_total_ = 0;
  std::string input_topic_, last_drop_;
  long missing_at_period_start_ = 0;
  StageTotals stage_totals_;
  std::map<std::string, long> dropped_total_, dropped_in_period_;
};

// ScanHealth published through diagnostic_updater as "<node>: scans". `extra` adds the node's
// own values and may raise the level.
class NodeDiagnostics {
 public:
  using Extra = std::function<void(HealthStatus&)>;
  NodeDiagnostics(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const std::string& node,
                  const std::string& hardware_id, double scan_period, Extra extra = {});

  StampStep received(const ros::Time& stamp) { return health_.received(stamp.toSec(), now()); }
  void processed(const StageTimes& times) { health_.processed(times); }
  void dropped(const std::string& reason, const std::string& detail = "") {
    health_.dropped(reason, detail);
  }
  // As ScanHealth::watch_input; the input's problem is also logged once, with the PointCloud2
  // topics the master knows (no_input_warning).
  void watch_input(const std::string& topic) { health_.watch_input(topic); }
  const ScanHealth& health() const { return health_; }

 private:
  static double now() { return steady_seconds(); }
  void fill(diagnostic_updater::DiagnosticStatusWrapper& status);

  std::string node_;
  ScanHealth health_;
  bool input_problem_logged_ = false;
  Extra extra_;
  diagnostic_updater::Updater updater_;
  ros::SteadyTimer timer_;
};

// The line a node logs when its input says nothing usable: `problem`, then where clouds are, of
// `cloud_topics` (the PointCloud2 topics published, the graph's own outputs left out), or that
// there are none.
std::string no_input_warning(const std::string& node, const std::string& problem,
                             const std::vector<std::string>& cloud_topics);

// The PointCloud2 topics the master knows, but the stages' own outputs (segmented_cloud, ...).
std::vector<std::string> published_cloud_topics();

// A weakest direction as the diagnostics give it: "x 0.99 y 0.05 z 0.00, sigma 0.312 m".
std::string direction_text(const Eigen::Vector3d& direction, double sigma_m);

}  // namespace adaptive_lego_loam::ros_bridge
