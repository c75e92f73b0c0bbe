#pragma once
// Where the sensor is at any time: driving along a path at a varying speed, or following a
// recorded trajectory (KITTI ground truth), with optional shaking from a rough road.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "adaptive_lego_loam/sim/path.h"
#include "adaptive_lego_loam/sim/speed_profile.h"

namespace adaptive_lego_loam::sim {

// A car body on its suspension over a rough lane (docs/simulator.md, "Rough road"): per axis a
// sum of sinusoids with seeded frequencies and phases, bounded by the amplitudes. The body modes
// bounce, roll and pitch it by centimetres and degrees at 1-2.5 Hz; wheel hop and the road's
// texture add a vibration of a fraction of a millimetre and hundredths of a degree at 10-30 Hz.
// The defaults are a rough lane; Shake() is a smooth ride.
struct ShakeParams {
  double vertical_m = 0.03;
  double roll_deg = 1.5;
  double pitch_deg = 1.5;
  double body_min_hz = 1.0, body_max_hz = 2.5;
  double vibration_vertical_m = 0.0002;
  double vibration_roll_pitch_deg = 0.02;
  double vibration_min_hz = 10.0, vibration_max_hz = 30.0;
};

class Shake {
 public:
  Shake() = default;
  Shake(const ShakeParams& params, uint64_t seed);
  // The offset of the sensor from its smooth pose (applied in the sensor frame): up by the
  // vertical offset, then turned by Rx(roll) Ry(pitch).
  Eigen::Isometry3d at(double time) const;
  // The vertical offset (m), roll and pitch (rad) at `time` (rows) and their first and second
  // time derivatives (columns 1 and 2).
  Eigen::Matrix3d axes(double time) const;

 private:
  struct Wave {
    double amplitude, frequency_hz, phase;
  };
  // The sum of the waves at `time`, or its first or second derivative.
  static double sum(const std::vector<Wave>& waves, double time, int derivative = 0);
  std::vector<Wave> vertical_, roll_, pitch_;
};

class Trajectory {
 public:
  virtual ~Trajectory() = default;
  // The sensor's pose in the world at `time` (s).
  virtual Eigen::Isometry3d sensor_pose(double time) const = 0;
  // The same without the rough road's shake, and the shake: sensor_pose(time) =
  // unshaken_pose(time) * shake().at(time). By default no shake.
  virtual Eigen::Isometry3d unshaken_pose(double time) const { return sensor_pose(time); }
  virtual const Shake& shake() const;
  // Start time of frame `frame`'s sweep.
  virtual double frame_time(int frame) const = 0;
  // How many frames the trajectory covers.
  virtual int frame_limit() const = 0;
};

// A vehicle driving along a path, the sensor `sensor_height` above the road, yawed along the path
// and pitched with its grade.
class PathTrajectory : public Trajectory {
 public:
  PathTrajectory(std::shared_ptr<const Path> path, const SpeedProfile& speed, double start_s,
                 double lateral_offset, double sensor_height, const Shake& shake,
                 double frame_period);
  Eigen::Isometry3d sensor_pose(double time) const override;
  Eigen::Isometry3d unshaken_pose(double time) const override;
  const Shake& shake() const override { return shake_; }
  double frame_time(int frame) const override { return frame * frame_period_; }
  int frame_limit() const override;
  double arc_length(double time) const { return start_s_ + speed_.distance(time); }

 private:
  std::shared_ptr<const Path> path_;
  SpeedProfile speed_;
  double start_s_, lateral_offset_, sensor_height_;
  Shake shake_;
  double frame_period_;
};

// Recorded sensor poses at given times, interpolated (linear position, slerp rotation).
class SampledTrajectory : public Trajectory {
 public:
  // `times` strictly increasing, one per pose; frame i starts at times[i] - times[0].
  SampledTrajectory(std::vector<double> times, std::vector<Eigen::Isometry3d> sensor_poses,
                    const Shake& shake);
  Eigen::Isometry3d sensor_pose(double time) const override;
  Eigen::Isometry3d unshaken_pose(double time) const override;
  const Shake& shake() const override { return shake_; }
  double frame_time(int frame) const override { return times_.at(frame) - times_.front(); }
  int frame_limit() const override { return static_cast<int>(times_.size()); }
  const std::vector<Eigen::Isometry3d>& smooth_poses() const { return poses_; }

 private:
  std::vector<double> times_;
  std::vector<Eigen::Isometry3d> poses_;
  Shake shake_;
};

// KITTI ground truth is the left camera's pose with camera axes (x right, y down, z forward).
// Returns the same motion with vehicle axes (x forward, y left, z up) in a world whose axes are
// the first camera's turned the same way: P' = C P C^-1, C mapping camera to vehicle axes. The
// camera's small offset from the LiDAR (KITTI's Tr) is not applied: the path is what matters.
// Rotations are re-orthonormalised (the files carry about 7 significant digits). Read the file
// with io/pose_files.h.
std::vector<Eigen::Isometry3d> camera_poses_to_vehicle_axes(
    const std::vector<Eigen::Isometry3d>& camera_poses);

}  // namespace adaptive_lego_loam::sim
