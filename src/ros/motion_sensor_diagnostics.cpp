#include "adaptive_lego_loam/ros/motion_sensor_diagnostics.h"

#include <cstdio>

namespace adaptive_lego_loam::ros_bridge {
namespace {

std::string number(double value, const char* format = "%.3g") {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string vector_text(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "%.3g %.3g %.3g", v.x(), v.y(), v.z());
  return text;
}

// The values one input shares with the other, its keys starting with `name`.
void add_input(const std::string& name, const std::string& topic, const InputStatus& input,
               bool in_use, long scans, long fallbacks, HealthStatus& status) {
  status.add(name + " topic", topic);
  status.add(name + " in use", in_use ? "yes" : "no");
  status.add(name + " rate (Hz)", number(input.rate_hz, "%.1f"));
  status.add(name + " latest gap (s)", number(input.latest_gap_s));
  status.add(name + " gaps (total)", std::to_string(input.gaps));
  status.add(name + " samples accepted", std::to_string(input.accepted));
  for (int kind = 0; kind < kSampleFaultKinds; ++kind) {
    status.add(name + " dropped: " + to_string(static_cast<SampleFault>(kind)),
               std::to_string(input.faults[kind]));
  }
  status.add(name + " scans used", std::to_string(scans));
  status.add(name + " scans LiDAR-only", std::to_string(fallbacks));
}

using Reported = MotionSensorDiagnostics::Reported;

// WARN on faults since the last report, and while the input has fallen back or fell back since.
void raise_input(const std::string& name, const std::string& topic, const InputStatus& input,
                 bool in_use, long scans, long fallbacks, Reported& before, HealthStatus& status) {
  if (input.accepted == 0 && input.dropped() == 0) {
    status.raise(HealthLevel::kWarn, "no " + name + " sample on " + topic);
  }
  if (input.dropped() > before.dropped) {
    status.raise(HealthLevel::kWarn, name + " samples dropped (faults)");
  }
  if ((scans > 0 && !in_use) || fallbacks > before.fallbacks) {
    status.raise(HealthLevel::kWarn, name + " fell back to LiDAR-only");
  }
  before = {input.dropped(), fallbacks};
}

}  // namespace

void MotionSensorDiagnostics::add_to(const MotionSensorRelay& relay, HealthStatus& status) {
  const MotionSensors* sensors = relay.sensors();
  if (!sensors) {
    status.add("motion sensors", "waiting for the first scan (" + std::to_string(relay.queued()) +
                                     " samples queued)");
    return;
  }
  const MotionSensorsStatus& s = sensors->status();
  if (relay.inputs().imu) {
    add_input("IMU", imu_topic_, s.imu, s.imu_in_use, s.imu_scans, s.imu_fallbacks, status);
    status.add("IMU restarts", std::to_string(s.imu_restarts));
    status.add("IMU LiDAR motions refused", std::to_string(s.lidar_rejections));
    status.add("IMU extrinsic", imu_extrinsic_);
    status.add("gyro bias (rad/s)", vector_text(s.gyro_bias));
    status.add("accel bias (m/s^2)", vector_text(s.accel_bias));
    raise_input("IMU", imu_topic_, s.imu, s.imu_in_use, s.imu_scans, s.imu_fallbacks, imu_reported_,
                status);
  }
  if (relay.inputs().wheel) {
    add_input("wheel odometry", wheel_topic_, s.wheel, s.wheel_in_use, s.wheel_scans,
              s.wheel_fallbacks, status);
    status.add("wheel odometry slips", std::to_string(s.wheel_slips));
    status.add("wheel odometry scale", number(s.wheel_scale, "%.4f"));
    status.add("wheel odometry scale sigma", number(s.wheel_scale_sigma, "%.2g"));
    status.add("wheel odometry extrinsic", wheel_extrinsic_);
    raise_input("wheel odometry", wheel_topic_, s.wheel, s.wheel_in_use, s.wheel_scans,
                s.wheel_fallbacks, wheel_reported_, status);
  }
  status.add("scans processed on the sensor timeout (total)", std::to_string(relay.timeouts()));
  status.add("scans without mapping feedback (total)", std::to_string(relay.missed_feedback()));
}

}  // namespace adaptive_lego_loam::ros_bridge
