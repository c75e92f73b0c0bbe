#pragma once
// feature_association's hand-over of the optional IMU and wheel odometry to the core's
// MotionSensors, so that the graph predicts each scan as run_sequence does. The samples are queued
// in the order they arrive. A scan is held until every configured input has sent a sample at or
// after its stamp and the mapping's feedback on the previous scan has come back, or until a
// timeout (an input silent for the timeout is not waited for: a gap holds one scan, not each); then
// the previous scan's feedback is applied (MotionSensors::update, nothing mapped when it never
// came), the samples up to the scan's stamp are handed over in arrival order (as run_sequence hands
// them over), and the scan is predicted. No ROS: times are steady-clock seconds, so that the logic
// is tested without a graph.

#include <Eigen/Geometry>
#include <array>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_sensors.h"

namespace adaptive_lego_loam::ros_bridge {

// The inputs feature_association subscribes (~imu_topic, ~wheel_odom_topic not empty).
struct MotionSensorInputs {
  bool imu = false;
  bool wheel = false;
  bool any() const { return imu || wheel; }
};

// Whether a held scan may be processed now.
enum class ScanRelease {
  kWait,     // samples up to its stamp, or the previous scan's feedback, may still come
  kReady,    // they came (an input that never sent a sample is not waited for)
  kTimeout,  // the timeout passed first
};

// A sample the core dropped, for the log: each input's first fault of each kind is logged, the
// rest counted.
struct SampleFaultReport {
  std::string input;  // "IMU" or "wheel odometry"
  double stamp = 0.0;
  SampleFault fault = SampleFault::kNotFinite;
  bool first = false;  // the first of its kind on this input
  std::string describe() const;
};

class MotionSensorRelay {
 public:
  // `timeout_s`: how long a scan waits for its samples, and for the previous scan's feedback.
  MotionSensorRelay(const Config& config, MotionSensorInputs inputs, double timeout_s);

  const MotionSensorInputs& inputs() const { return inputs_; }
  // The extrinsics found in TF, replacing the config's; after the first scan the core starts
  // over with them (an input that named its frame late).
  void set_lidar_from_imu(const Eigen::Isometry3d& pose);
  void set_lidar_from_base(const Eigen::Isometry3d& pose);
  bool started() const { return sensors_.has_value(); }

  // Samples as they arrive, on their own clocks (the config's time offsets are added here as in
  // the core). A sample more than a second older than the newest of its input means time went
  // back (a bag played again): that input's queue starts over.
  void add_imu(const ImuSample& sample, double now_s);
  void add_wheel(const WheelOdometrySample& sample, double now_s);
  // The mapping's result for the scan at `stamp`: its mapped motion when it was matched, the
  // information the LiDAR's correspondences had of it, and whether the motion prior held a
  // direction (MotionSensors::update's). Used when it is the last predicted scan's; a late one (a
  // newer scan was predicted without it) is ignored.
  void add_feedback(double stamp, const std::optional<Eigen::Isometry3d>& motion,
                    const Matrix6d& information, bool prior_held = false);

  // Whether the scan at `stamp`, complete since `waiting_since_s`, may be processed at `now_s`.
  ScanRelease release(double stamp, double waiting_since_s, double now_s) const;
  // What the scan at `stamp` still waits for: "IMU samples up to its stamp (the newest at 4.295
  // s), the mapping's feedback on the previous scan"; empty when nothing.
  std::string missing(double stamp) const;
  // Processes the scan at `stamp` (released as `why`): the previous scan's feedback (or its
  // absence), the samples up to `stamp`, the prediction. nullptr when no input covers the scan
  // (LiDAR-only), as the offline pipeline passes it to the odometry and the mapping.
  const MotionPrediction* predict(double stamp, double sweep_period, ScanRelease why, double now_s);
  // The faults of the samples handed over since the last call.
  std::vector<SampleFaultReport> take_faults();
  // Time went back: the core starts over at the next scan (the queues keep what they hold).
  void reset();

  // The core's stage; nullptr before the first scan.
  const MotionSensors* sensors() const { return sensors_ ? &*sensors_ : nullptr; }
  long timeouts() const { return timeouts_; }                // scans processed on the timeout
  long missed_feedback() const { return missed_feedback_; }  // ... without the previous feedback
  long late_feedback() const { return late_feedback_; }      // feedback that came too late
  long queued() const { return static_cast<long>(imu_queue_.size() + wheel_queue_.size()); }

 private:
  struct InputQueue {
    std::optional<double> newest;  // the newest stamp received (its clock + offset)
    std::optional<double> last_arrival_s;
    std::array<bool, kSampleFaultKinds> reported{};
    // It has sent samples, none at or after `stamp` yet.
    bool behind(double stamp) const;
    // Nothing came for the timeout.
    bool silent(double now_s, double timeout_s) const;
    // Notes a sample at `stamp` (offset added); false when time went back (clear the queue).
    bool receive(double stamp, double now_s);
  };
  void feed(double stamp);
  void report(const char* input, double stamp, const std::optional<SampleFault>& fault,
              InputQueue& queue);

  Config config_;
  MotionSensorInputs inputs_;
  double timeout_s_;
  std::optional<MotionSensors> sensors_;
  std::deque<ImuSample> imu_queue_;
  std::deque<WheelOdometrySample> wheel_queue_;
  InputQueue imu_, wheel_;
  // The last predicted scan, while its feedback has not come, and when it was predicted.
  std::optional<double> awaiting_feedback_;
  double predicted_at_s_ = 0.0;
  std::vector<SampleFaultReport> faults_;
  long timeouts_ = 0, missed_feedback_ = 0, late_feedback_ = 0;
};

// A pose as a config's extrinsic: roll, pitch, yaw (deg, R = Rz(yaw) Ry(pitch) Rx(roll), as
// pose_from_rpy_xyz reads them) and x, y, z (m).
void set_extrinsic(const Eigen::Isometry3d& pose, std::vector<double>& rpy_deg,
                   std::vector<double>& xyz_m);

}  // namespace adaptive_lego_loam::ros_bridge
