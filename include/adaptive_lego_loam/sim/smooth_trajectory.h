#pragma once
// The one smooth curve every simulated sensor moves along: another trajectory's poses at its
// frame times joined by a C2 spline of positions and a C1 spline of rotations, with the rough
// road's shake on top. The LiDAR's column poses, the ground truth, the IMU and the wheel
// odometry all come from it, so the IMU's readings are the exact derivatives of the poses the
// scans were rendered from.

#include <memory>
#include <vector>

#include "adaptive_lego_loam/sim/kinematics.h"
#include "adaptive_lego_loam/sim/rotation_spline.h"
#include "adaptive_lego_loam/sim/smoothing_spline.h"
#include "adaptive_lego_loam/sim/trajectory.h"

namespace adaptive_lego_loam::sim {

class SmoothTrajectory : public Trajectory {
 public:
  // Knots: `base`'s unshaken poses at its frame times 0 to frames + 1 (fewer when it has fewer;
  // with one, it stands there).
  // position_cutoff_hz 0: the positions' spline passes through every knot (a frame's pose is the
  // base's); above 0 it is the smoothing spline of that cutoff (SmoothingSpline), for recorded
  // poses whose noise would otherwise be differentiated into accelerations no vehicle makes.
  // Rotations pass through every knot.
  SmoothTrajectory(std::shared_ptr<const Trajectory> base, int frames, double position_cutoff_hz);

  Eigen::Isometry3d sensor_pose(double time) const override;
  Eigen::Isometry3d unshaken_pose(double time) const override;
  const Shake& shake() const override { return base_->shake(); }
  double frame_time(int frame) const override { return base_->frame_time(frame); }
  int frame_limit() const override { return frame_limit_; }

  // The sensor's kinematics in the world at `time`, the shake included: what the LiDAR and the
  // IMU, mounted on the vehicle's body, move with.
  Kinematics motion(double time) const;
  // The same without the shake: the chassis the body shakes on, at the sensor's place, which
  // the wheels roll with.
  Kinematics unshaken_motion(double time) const;
  double position_cutoff_hz() const { return position_cutoff_hz_; }
  // The trajectory it joins smoothly.
  const Trajectory& base() const { return *base_; }

 private:
  Kinematics shake_motion(double time) const;

  std::shared_ptr<const Trajectory> base_;
  double position_cutoff_hz_;
  int frame_limit_ = 0;
  SmoothingSpline positions_;
  RotationSpline rotations_;
};

// A sensor's sample times from `from` to `to` (inclusive, to a nanosecond) at `rate_hz`:
// from + k / rate_hz.
std::vector<double> sample_times(double from, double to, double rate_hz);

}  // namespace adaptive_lego_loam::sim
