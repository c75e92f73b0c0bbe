#pragma once
// The optional motion sensors' stage (docs/METHOD.md, "Motion sensors"), before the odometry:
// takes the IMU's and the wheel odometry's samples as they come, checks them, and for each scan
// says how the sensor moved along its sweep and since the previous scan and where gravity points
// (MotionPrediction); after mapping it learns from the LiDAR's motion (biases, the wheel's scale,
// the velocity). Without samples it predicts nothing and the pipeline is LiDAR-only.

#include <deque>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/motion_sensors/inertial_filter.h"
#include "adaptive_lego_loam/core/motion_sensors/input_monitor.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"
#include "adaptive_lego_loam/core/motion_sensors/samples.h"
#include "adaptive_lego_loam/core/motion_sensors/wheel_odometry.h"

namespace adaptive_lego_loam {

// What the stage has seen and done, for /diagnostics and summary.json.
struct MotionSensorsStatus {
  InputStatus imu, wheel;
  bool imu_in_use = false;                      // the latest scan was predicted by the IMU's filter
  bool wheel_in_use = false;                    // ... used the wheel odometry
  long imu_scans = 0, wheel_scans = 0;          // scans each input took part in
  long imu_fallbacks = 0, wheel_fallbacks = 0;  // scans an input did not cover (LiDAR-only)
  long imu_restarts = 0;                        // the filter started again after a gap
  long lidar_rejections = 0;                    // LiDAR motions the filter's gate refused
  long wheel_slips = 0;                         // wheel samples or scans refused as slip
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // rad/s, IMU frame
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // m/s^2, IMU frame
  double wheel_scale = 1.0, wheel_scale_sigma = 0.0;
};

class MotionSensors {
 public:
  // `sweep_steps`: the sweep's poses are given at this many intervals (de-skewing).
  explicit MotionSensors(const Config& config, int sweep_steps = 20);

  // A sample as it arrives, stamped on its own clock (the config's time offset is added). A fault
  // (SampleFault) is counted, the sample dropped, and returned for logging.
  std::optional<SampleFault> add_imu(ImuSample sample);
  std::optional<SampleFault> add_wheel(WheelOdometrySample sample);
  // Whether any sample of either input was accepted: the pipeline is LiDAR-only until then.
  bool active() const { return status_.imu.accepted > 0 || status_.wheel.accepted > 0; }

  // Before the scan whose sweep ends at `stamp` (a sweep of `sweep_period` s): the samples up to
  // `stamp` integrated. Empty when no input covers the scan.
  const MotionPrediction& predict(double stamp, double sweep_period);
  // After mapping the same scan: its mapped motion since the previous scan (the LiDAR frame) and
  // the information the LiDAR's correspondences alone have of it (right perturbations,
  // MotionPrior's); nothing when the scan was not mapped. The mapping's prior holds only the
  // directions the LiDAR leaves open, where its information is nil: the filter does not learn its
  // own prediction back.
  // `prior_held`: the mapping's prior held a direction of this scan; its motion does not teach
  // the wheel odometry its scale (the scale would learn its own prediction back).
  void update(const std::optional<Eigen::Isometry3d>& mapped_motion, const Matrix6d& information,
              bool prior_held = false);

  const MotionSensorsStatus& status() const { return status_; }
  const InertialFilter& filter() const { return filter_; }
  const Eigen::Isometry3d& lidar_from_imu() const { return lidar_from_imu_; }
  const Eigen::Isometry3d& lidar_from_base() const { return lidar_from_base_; }

 private:
  struct TimedPose {
    double stamp;
    Eigen::Isometry3d pose;  // on path_
  };
  // Propagates the filter through the IMU samples up to `stamp`, with the wheel odometry's
  // velocities as measurements, recording the IMU's poses.
  void propagate_to(double stamp);
  void record_pose();
  // The IMU's pose at `stamp` from the recorded poses.
  Eigen::Isometry3d recorded_pose(double stamp) const;
  SweepMotion sweep_motion(double stamp, double sweep_period) const;
  void predict_with_filter(double stamp, double sweep_period);
  // A wheel velocity as the filter's measurement (slip when its gate refuses it).
  void apply_wheel(const WheelOdometrySample& wheel, const Eigen::Vector3d& gyro);
  void predict_with_wheel(double stamp);
  void start_filter(const Eigen::Isometry3d& lidar_motion);
  void learn_wheel_scale(const Eigen::Isometry3d& lidar_motion, const Matrix6d& information);
  // The marginal variance of the base's forward distance the information gives (m^2).
  double forward_variance(const Matrix6d& information) const;
  void drop_old_samples(double before);

  ImuParams imu_params_;
  WheelOdometryParams wheel_params_;
  int sweep_steps_;
  Eigen::Isometry3d lidar_from_imu_, lidar_from_base_;
  InputMonitor imu_monitor_, wheel_monitor_;
  std::deque<ImuSample> imu_samples_;
  std::deque<WheelOdometrySample> wheel_samples_;
  InertialFilter filter_;
  WheelScale wheel_scale_;
  std::optional<ImuSample> last_imu_;  // the last sample the filter integrated
  double last_wheel_stamp_ = -1e300;   // of the last wheel sample the filter used
  // The IMU's path as the filter's steps move it, without the jumps of its corrections: what
  // de-skews a sweep must be continuous.
  Eigen::Isometry3d path_ = Eigen::Isometry3d::Identity();
  std::deque<TimedPose> recorded_;
  std::optional<double> previous_stamp_;  // the last scan's
  std::optional<double> interval_start_;  // the scan before the current one's
  double stamp_ = 0.0;
  struct TimedSpeed {
    double stamp;
    double speed;  // the base's forward speed, m/s
  };
  std::optional<TimedSpeed> reference_speed_;  // the last one known (without an IMU: slips)
  int motions_in_a_row_ = 0;                 // mapped motions (update()) since a scan went unmapped
  int refusals_in_a_row_ = 0;                // LiDAR motions the filter's gate refused
  std::optional<double> refused_since_;      // wheel samples refused in a row since
  std::optional<double> last_refusal_;       // of a wheel sample
  std::optional<WheelMotion> wheel_motion_;  // this scan's, for the scale
  MotionPrediction prediction_;
  MotionSensorsStatus status_;
};

}  // namespace adaptive_lego_loam
