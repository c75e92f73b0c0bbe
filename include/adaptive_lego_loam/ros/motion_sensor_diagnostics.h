#pragma once
// feature_association's motion sensors on /diagnostics: for each input in use its topic, whether
// the latest scan used it, its rate, gaps, samples accepted and dropped by fault, the scans it
// took part in and those that fell back to LiDAR-only, where its extrinsic came from; the IMU's
// biases and the wheel odometry's scale; the scans processed on the timeout. WARN while an input
// that was in use is out (LiDAR-only) or when it fell back since the last report, when an input
// dropped samples since the last report, and when a configured input has sent nothing.

#include <string>
#include <utility>

#include "adaptive_lego_loam/ros/motion_sensor_relay.h"
#include "adaptive_lego_loam/ros/node_diagnostics.h"

namespace adaptive_lego_loam::ros_bridge {

class MotionSensorDiagnostics {
 public:
  // The inputs' topics (empty: not configured).
  MotionSensorDiagnostics(std::string imu_topic, std::string wheel_topic)
      : imu_topic_(std::move(imu_topic)), wheel_topic_(std::move(wheel_topic)) {}
  // Where each extrinsic came from ("TF velodyne -> imu" or "config").
  void set_imu_extrinsic_source(const std::string& source) { imu_extrinsic_ = source; }
  void set_wheel_extrinsic_source(const std::string& source) { wheel_extrinsic_ = source; }

  // Adds the values and raises the level; remembers the counts to tell what is new next time.
  void add_to(const MotionSensorRelay& relay, HealthStatus& status);

  // An input's counts at the last report.
  struct Reported {
    long dropped = 0, fallbacks = 0;
  };

 private:
  std::string imu_topic_, wheel_topic_;
  std::string imu_extrinsic_ = "config", wheel_extrinsic_ = "config";
  Reported imu_reported_, wheel_reported_;
};

}  // namespace adaptive_lego_loam::ros_bridge
