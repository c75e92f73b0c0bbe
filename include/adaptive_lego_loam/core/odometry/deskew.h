#pragma once
// Removing the motion distortion of a sweep: each point is moved to where it would have been
// measured at the end of the sweep, assuming the sensor moved at constant velocity.

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"

namespace adaptive_lego_loam {

// Each point's place in the sweep, 0 at its start and 1 at its end. From the points' time field
// when they have one and its span is plausible (0.5 to 1.5 scan periods), else from the azimuth:
// the sensor turns clockwise seen from above, starting at `start_azimuth` (rad, atan2(y, x) of
// the sweep's first point). Returns whether the time field was used.
bool sweep_fractions(const std::vector<ScanPoint>& points, bool has_time, double start_azimuth,
                     double scan_period, std::vector<float>& fractions);

// Moves points measured along a sweep during which the sensor moved by `sweep_motion` (pose at
// the sweep's end in the frame of its start) into the frame of the sweep's end.
void deskew_to_sweep_end(const Eigen::Isometry3d& sweep_motion, const std::vector<float>& fractions,
                         std::vector<ScanPoint>& points);

// The same along a sweep whose poses the motion sensors measured (SweepMotion: an IMU's rotation
// and the filter's velocity, not a constant velocity).
void deskew_to_sweep_end(const SweepMotion& sweep, const std::vector<float>& fractions,
                         std::vector<ScanPoint>& points);

// The pose a fraction `s` of the way along `motion` (rotation by slerp, translation linear).
Eigen::Isometry3d interpolate_motion(const Eigen::Isometry3d& motion, double s);

}  // namespace adaptive_lego_loam
