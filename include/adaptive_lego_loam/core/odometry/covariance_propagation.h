#pragma once
// A pose's covariance carried along a chain of motions: the odometry's pose (each scan's
// registration adds its own), and the fused pose (mapping's, then the odometry since). Both are
// over [rotation vector (rad), translation (m)] of a right perturbation, pose * exp(xi), in the
// frame of the pose they belong to (observability.h's convention).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"
#include "adaptive_lego_loam/core/odometry/observability.h"

namespace adaptive_lego_loam {

// The covariance of pose * motion: the pose's turned into the motion's end frame plus the
// motion's own. Variances past `max_variance` are held there: a direction the chain lost once
// stays as unknown as covariance_from_information makes it, not unknown many times over.
Matrix6d compose_covariance(const Matrix6d& pose_covariance, const Eigen::Isometry3d& motion,
                            const Matrix6d& motion_covariance,
                            double max_variance = kUnknownVariance);

// What `motion` added to a chain whose covariance went from `before` to `after` over it
// (compose_covariance undone; negative parts from the variances held at max_variance dropped).
Matrix6d covariance_added(const Matrix6d& before, const Eigen::Isometry3d& motion,
                          const Matrix6d& after);

}  // namespace adaptive_lego_loam
