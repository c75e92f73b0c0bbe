#pragma once
// The wheel odometry on its own: its twists integrated into the base frame's motion over an
// interval, the information that motion carries (forward distance and yaw; no roll or pitch),
// and its scale error estimated against the LiDAR where the LiDAR sees the motion along the road.

#include <Eigen/Geometry>
#include <deque>
#include <optional>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"
#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam {

// The base frame's motion over an interval, as the odometry reports it (scale not corrected),
// and the reported forward distance.
struct WheelMotion {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  double distance = 0.0;           // forward, m, signed
  double distance_variance = 0.0;  // from the reported (or configured) speed noise
  double yaw_variance = 0.0;
};

// Integrates `samples` (ordered) over (from, to]: each sample's twist holds from its stamp to the
// next one's or `to`, and the one before `from` holds from it. Nothing when no
// sample reaches back to `from`, or a sample would hold longer than params.max_gap_s.
std::optional<WheelMotion> integrate_wheel(const std::deque<WheelOdometrySample>& samples,
                                           double from, double to,
                                           const WheelOdometryParams& params);

// A motion of the base frame, its distance scaled by `scale` (known to `scale_sigma`), as a
// prior of the LiDAR's motion: forward distance and yaw from the odometry, no sideways or
// vertical motion within a few percent of the distance (a vehicle does not slide), nothing of
// roll and pitch. `lidar_from_base`: the base frame's pose in the LiDAR frame.
MotionPrior wheel_prior(const WheelMotion& wheel, double scale, double scale_sigma,
                        const Eigen::Isometry3d& lidar_from_base);

// The odometry's scale (true distance over reported) as a scalar Kalman filter: each interval
// where the LiDAR measured the forward distance well is a measurement; the scale may drift
// slowly (tyre pressure, load).
class WheelScale {
 public:
  // Starts at 1 with `sigma` (the 1-3 % a wheel odometry is off by).
  explicit WheelScale(double sigma = 0.03) : variance_(sigma * sigma) {}
  // An interval of `reported` m in which the LiDAR measured `measured` m to `measured_sigma`;
  // false when it is too far from the scale to be one (a slip, a LiDAR gone wrong): not used.
  bool add(double reported, double measured, double measured_sigma);
  double scale() const { return scale_; }
  double sigma() const;

 private:
  double scale_ = 1.0;
  double variance_;
};

}  // namespace adaptive_lego_loam
