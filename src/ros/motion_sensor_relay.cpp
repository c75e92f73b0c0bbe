#include "adaptive_lego_loam/ros/motion_sensor_relay.h"

#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

namespace adaptive_lego_loam::ros_bridge {
namespace {

// Samples this much older than the newest of their input: time went back (as StampMatcher).
constexpr double kJumpBack = 1.0;  // s
constexpr double kDeg = 180.0 / M_PI;

}  // namespace

std::string SampleFaultReport::describe() const {
  char line[160];
  std::snprintf(line, sizeof(line), "%s sample at %.6f s dropped: %s", input.c_str(), stamp,
                to_string(fault));
  return line;
}

bool MotionSensorRelay::InputQueue::behind(double stamp) const {
  return last_arrival_s && *newest < stamp;
}

bool MotionSensorRelay::InputQueue::silent(double now_s, double timeout_s) const {
  return !last_arrival_s || now_s - *last_arrival_s >= timeout_s;
}

bool MotionSensorRelay::InputQueue::receive(double stamp, double now_s) {
  last_arrival_s = now_s;
  const bool went_back = newest && stamp + kJumpBack < *newest;
  if (!newest || stamp > *newest || went_back) newest = stamp;
  return !went_back;
}

MotionSensorRelay::MotionSensorRelay(const Config& config, MotionSensorInputs inputs,
                                     double timeout_s)
    : config_(config), inputs_(inputs), timeout_s_(timeout_s) {}

void MotionSensorRelay::set_lidar_from_imu(const Eigen::Isometry3d& pose) {
  set_extrinsic(pose, config_.imu.extrinsic_rpy_deg, config_.imu.extrinsic_xyz_m);
  reset();
}

void MotionSensorRelay::set_lidar_from_base(const Eigen::Isometry3d& pose) {
  set_extrinsic(pose, config_.wheel_odometry.extrinsic_rpy_deg,
                config_.wheel_odometry.extrinsic_xyz_m);
  reset();
}

void MotionSensorRelay::add_imu(const ImuSample& sample, double now_s) {
  if (!imu_.receive(sample.stamp + config_.imu.time_offset_s, now_s)) imu_queue_.clear();
  imu_queue_.push_back(sample);
}

void MotionSensorRelay::add_wheel(const WheelOdometrySample& sample, double now_s) {
  if (!wheel_.receive(sample.stamp + config_.wheel_odometry.time_offset_s, now_s)) {
    wheel_queue_.clear();
  }
  wheel_queue_.push_back(sample);
}

void MotionSensorRelay::add_feedback(double stamp, const std::optional<Eigen::Isometry3d>& motion,
                                     const Matrix6d& information, bool prior_held) {
  if (!awaiting_feedback_ || *awaiting_feedback_ != stamp) {
    ++late_feedback_;
    return;
  }
  sensors_->update(motion, information, prior_held);
  awaiting_feedback_.reset();
}

ScanRelease MotionSensorRelay::release(double stamp, double waiting_since_s, double now_s) const {
  bool behind = false, coming = false;
  for (const auto& [used, queue] : {std::pair{inputs_.imu, &imu_}, {inputs_.wheel, &wheel_}}) {
    if (!used || !queue->behind(stamp)) continue;
    behind = true;
    coming |= !queue->silent(now_s, timeout_s_);
  }
  if (!behind && !awaiting_feedback_) return ScanRelease::kReady;
  // The samples are waited for from when this scan was complete, while their input sends (one
  // silent for the timeout has stopped: the scans go on without it, not each after a timeout);
  // the feedback from when the previous scan was predicted.
  const bool samples_due = coming && now_s - waiting_since_s < timeout_s_;
  const bool feedback_due = awaiting_feedback_ && now_s - predicted_at_s_ < timeout_s_;
  return samples_due || feedback_due ? ScanRelease::kWait : ScanRelease::kTimeout;
}

std::string MotionSensorRelay::missing(double stamp) const {
  std::string text;
  const auto add = [&](const std::string& what) { text += (text.empty() ? "" : ", ") + what; };
  char line[96];
  for (const auto& [used, name, queue] :
       {std::tuple{inputs_.imu, "IMU", &imu_}, {inputs_.wheel, "wheel odometry", &wheel_}}) {
    if (!used || !queue->behind(stamp)) continue;
    std::snprintf(line, sizeof(line), "%s samples up to its stamp (the newest at %.3f s)", name,
                  *queue->newest);
    add(line);
  }
  if (awaiting_feedback_) add("the mapping's feedback on the previous scan");
  return text;
}

const MotionPrediction* MotionSensorRelay::predict(double stamp, double sweep_period,
                                                   ScanRelease why, double now_s) {
  if (!sensors_) sensors_.emplace(config_);
  if (awaiting_feedback_) {
    // The previous scan's mapping never answered: as a scan that was not mapped.
    sensors_->update(std::nullopt, Matrix6d::Zero());
    awaiting_feedback_.reset();
    ++missed_feedback_;
  }
  timeouts_ += why == ScanRelease::kTimeout;
  feed(stamp);
  if (!sensors_->active()) return nullptr;
  const MotionPrediction& prediction = sensors_->predict(stamp, sweep_period);
  awaiting_feedback_ = stamp;
  predicted_at_s_ = now_s;
  return prediction.empty() ? nullptr : &prediction;
}

void MotionSensorRelay::feed(double stamp) {
  // As run_sequence: each queue's samples in arrival order up to the first one after the stamp.
  while (!imu_queue_.empty() && imu_queue_.front().stamp + config_.imu.time_offset_s <= stamp) {
    const ImuSample& sample = imu_queue_.front();
    report("IMU", sample.stamp, sensors_->add_imu(sample), imu_);
    imu_queue_.pop_front();
  }
  while (!wheel_queue_.empty() &&
         wheel_queue_.front().stamp + config_.wheel_odometry.time_offset_s <= stamp) {
    const WheelOdometrySample& sample = wheel_queue_.front();
    report("wheel odometry", sample.stamp, sensors_->add_wheel(sample), wheel_);
    wheel_queue_.pop_front();
  }
}

void MotionSensorRelay::report(const char* input, double stamp,
                               const std::optional<SampleFault>& fault, InputQueue& queue) {
  if (!fault) return;
  bool& reported = queue.reported[static_cast<int>(*fault)];
  faults_.push_back({input, stamp, *fault, !reported});
  reported = true;
}

std::vector<SampleFaultReport> MotionSensorRelay::take_faults() {
  std::vector<SampleFaultReport> faults;
  faults.swap(faults_);
  return faults;
}

void MotionSensorRelay::reset() {
  sensors_.reset();
  awaiting_feedback_.reset();
}

void set_extrinsic(const Eigen::Isometry3d& pose, std::vector<double>& rpy_deg,
                   std::vector<double>& xyz_m) {
  // R = Rz(yaw) Ry(pitch) Rx(roll). Yaw from the first column; roll and pitch from what is left,
  // Rz(yaw)^T R = Ry(pitch) Rx(roll), which gives R back to rounding even near pitch +-90 deg,
  // where yaw and roll are barely told apart.
  const Eigen::Matrix3d r = pose.rotation();
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  const Eigen::Matrix3d rest = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * r;
  const double roll = std::atan2(-rest(1, 2), rest(1, 1));
  const double pitch = std::atan2(-rest(2, 0), rest(0, 0));
  rpy_deg = {roll * kDeg, pitch * kDeg, yaw * kDeg};
  xyz_m = {pose.translation().x(), pose.translation().y(), pose.translation().z()};
}

}  // namespace adaptive_lego_loam::ros_bridge
