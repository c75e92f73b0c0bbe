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
//          or no scan came for 2 s after the first;
//   OK     otherwise (also before the first scan).

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

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
  void dropped(const std::string& reason);
  // The status of the period since the last call; a new period starts.
  HealthStatus close_period(double now_s);

  long dropped_total() const;
  const std::map<std::string, long>& dropped_by_reason() const { return dropped_total_; }
  long missing_total() const { return stamps_.missing(); }

 private:
  double period_;
  ScanStamps stamps_;
  std::optional<double> last_received_s_, period_start_s_;
  int received_ = 0, processed_ = 0;
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
  void dropped(const std::string& reason) { health_.dropped(reason); }
  const ScanHealth& health() const { return health_; }

 private:
  static double now() { return steady_seconds(); }
  void fill(diagnostic_updater::DiagnosticStatusWrapper& status);

  ScanHealth health_;
  Extra extra_;
  diagnostic_updater::Updater updater_;
  ros::SteadyTimer timer_;
};

}  // namespace adaptive_lego_loam::ros_bridge
