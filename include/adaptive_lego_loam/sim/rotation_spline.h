#pragma once
// Rotations through given ones at given times with a continuous angular velocity (C1): on each
// interval R(t) = R_i Exp(theta(t)), theta a cubic from 0 to Log(R_i^T R_i+1) whose slopes at
// the ends give the knots' angular velocities. Those come from a natural cubic spline through
// the summed increments, so that the rotation is also about C2 where the increments are small.

#include <Eigen/Core>
#include <vector>

namespace adaptive_lego_loam::sim {

class RotationSpline {
 public:
  // `times` strictly increasing, at least two, one per rotation; consecutive rotations less than
  // pi apart. Throws std::invalid_argument otherwise.
  RotationSpline(std::vector<double> times, std::vector<Eigen::Matrix3d> rotations);

  struct State {
    Eigen::Matrix3d rotation;
    Eigen::Vector3d angular_velocity;      // rad/s, in the rotated frame's own axes
    Eigen::Vector3d angular_acceleration;  // rad/s^2, likewise
  };
  // Exactly the given rotation at a knot; beyond the ends it turns on at the end's rate.
  State at(double time) const;

 private:
  std::vector<double> times_;
  std::vector<Eigen::Matrix3d> rotations_;
  std::vector<Eigen::Vector3d> increments_;  // Log(R_i^T R_i+1)
  std::vector<Eigen::Vector3d> rates_;       // angular velocity at each knot
  std::vector<Eigen::Vector3d> end_slopes_;  // d theta / dt at each interval's end
};

// SO(3)'s right Jacobian: the angular velocity of R Exp(theta(t)) is right_jacobian(theta) *
// d theta / dt.
Eigen::Matrix3d right_jacobian(const Eigen::Vector3d& theta);

}  // namespace adaptive_lego_loam::sim
