#pragma once
// How well a registration's information (normalised by the measurement noise: 1/m^2, 1/rad^2)
// fixes each direction of the motion: the translation's uncertainty along its principal
// directions once the rotation is marginalised out, and the rotation's once the translation is.
// A direction the scene does not constrain has an infinite sigma.

#include <Eigen/Core>

namespace adaptive_lego_loam {

struct Observability {
  // 1-sigma (m) along each principal direction of the translation, largest first, and the
  // directions (unit columns, in the frame the information is in).
  Eigen::Vector3d translation_sigma = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Matrix3d translation_directions = Eigen::Matrix3d::Identity();
  Eigen::Vector3d rotation_sigma = Eigen::Vector3d::Constant(INFINITY);  // rad, largest first
  Eigen::Matrix3d rotation_directions = Eigen::Matrix3d::Identity();
  // The least-constrained translation direction and its sigma.
  Eigen::Vector3d weakest_direction() const { return translation_directions.col(0); }
  double weakest_sigma() const { return translation_sigma(0); }
};

// From the information of [rotation vector, translation] (6 x 6, symmetric, possibly singular).
Observability observability(const Eigen::Matrix<double, 6, 6>& information);

// What a published covariance says of a direction nothing fixes (m^2 or rad^2: 100 m): a pose
// covariance must be finite.
constexpr double kUnknownVariance = 1e4;

// The covariance the information implies; along a direction it leaves open, or fixes worse than
// `unknown_variance`, that variance.
Eigen::Matrix<double, 6, 6> covariance_from_information(
    const Eigen::Matrix<double, 6, 6>& information, double unknown_variance = kUnknownVariance);

// The information with its translation along the unit `direction` kept only in the share `keep`
// (the information along it times keep^2): what correspondences say along a direction the scene's
// structure does not constrain (the ambient filter's weak direction, keep = 1 - mu) is mostly
// not the scene's: rings and edges fixed to the sensor.
Eigen::Matrix<double, 6, 6> discounted_along(const Eigen::Matrix<double, 6, 6>& information,
                                             const Eigen::Vector3d& direction, double keep);

// `translation` with its component along the unit `direction` taken from `held`: a motion held at
// its guess along a direction the scan does not fix (the follow test), free across it.
Eigen::Vector3d held_along(const Eigen::Vector3d& translation, const Eigen::Vector3d& held,
                           const Eigen::Vector3d& direction);

}  // namespace adaptive_lego_loam
