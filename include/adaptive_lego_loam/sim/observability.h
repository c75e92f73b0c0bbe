#pragma once
// The true observability of a simulated scan: how well its returns, without noise and with the
// true normals of the surfaces they hit, fix the sensor's pose. It is the information matrix of
// point-to-plane residuals, sum_i J_i^T J_i / sigma^2 with J_i = [(p_i x n_i)^T, n_i^T]: rotation
// about x, y, z (rad), then translation along x, y, z (m), in the sensor frame at the scan's time.
// A degenerate scene (a tunnel's smooth walls) leaves a direction without information.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_lego_loam/sim/simulator.h"

namespace adaptive_lego_loam::sim {

using Information6 = Eigen::Matrix<double, 6, 6>;

// `points` and unit `normals` one per point, in the frame the information is wanted in.
Information6 point_to_plane_information(const std::vector<Eigen::Vector3f>& points,
                                        const std::vector<Eigen::Vector3f>& normals,
                                        double sigma_m);

// Of a simulated scan's exact points and normals. Points on moving objects are left out (they do
// not constrain the sensor's motion); the ground counts (it fixes z, roll and pitch).
Information6 scan_information(const SimFrame& frame, double sigma_m);

// The translation's weakest direction once the rotation is marginalised out (the Schur
// complement of the rotation block): the direction of largest variance and its standard
// deviation (m), infinite when the scan does not fix the translation along it at all.
struct WeakestTranslation {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  double sigma_m = 0.0;
};
WeakestTranslation weakest_translation(const Information6& information);

// The sigma of a sensor with this range noise: the noise itself, or 1 m without noise (then the
// information is sum_i J_i^T J_i).
double observability_sigma(double range_noise_m);

// observability.csv: comment lines saying what the numbers are, then a line per scan: its index
// and the 36 entries of its information matrix, row by row.
std::string observability_header(double range_noise_m);
std::string observability_line(int frame, const Information6& information);

}  // namespace adaptive_lego_loam::sim
