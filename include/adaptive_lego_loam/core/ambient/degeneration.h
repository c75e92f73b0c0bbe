#pragma once
// docs/METHOD.md, steps 7 and 8: the degeneration degree mu from the horizontal parts of the
// weighted normals, the weakly constrained direction, and the adaptive beta0.

#include <Eigen/Core>
#include <vector>

#include "adaptive_lego_loam/core/ambient/skeleton_normals.h"

namespace adaptive_lego_loam {

struct Degeneration {
  bool valid = false;  // false when no normal had a horizontal part: mu unknown
  double mu = 0.0;     // in [0, 1]; 1 = all constraints along one horizontal direction
  double k = 1.0;      // sum |x'| / sum |y'| (>= 1), infinite when sum |y'| = 0
  // Unit horizontal direction along which the scan constrains least (sensor frame): the
  // eigenvector of the smaller eigenvalue of sum v v^T.
  Eigen::Vector2d weak_direction = Eigen::Vector2d::UnitX();
  int normals = 0;
};

// v_i = weight_i * (n_x, n_y); the second-moment matrix sum v v^T (normals have no sign, so not a
// centred covariance) gives the eigenbasis; k = sum |x'_i| / sum |y'_i|; mu = 1 - 1/k.
Degeneration degeneration_from_normals(const std::vector<NormalFeature>& normals);

// mu weighed by the evidence behind it: with fewer than `evidence_normals` skeleton normals it is
// pulled toward 1 in proportion (little structure constrains little), mu' = 1 - (1 - mu) *
// normals / evidence_normals; unchanged with as many or more, or when evidence_normals is 0.
double mu_with_evidence(double mu, int normals, int evidence_normals);

// The share of the clustered scene that is structure: the skeleton, plus the fragments (clustered
// points not in the skeleton) in proportion to how much smoother than noise they are,
// (skeleton + e fragments) / clustered with e = clamp((smoothness - floor) / (1 - floor), 0, 1).
// With floor 1 it is the skeleton's share alone; 0 without clustered points.
double structure_share(int skeleton_points, int clustered_points, double fragment_smoothness,
                       double smoothness_floor);

// mu shifted by how much of the clustered scene is structure (structure_share(): foliage breaks up
// under the strict depth clustering and its fragments are rough, walls hold together, rails break
// into smooth fragments): mu' = clamp(mu + weight (share - reference_share), 0, 1); unchanged
// when weight is 0.
double mu_with_structure(double mu, double share, double weight, double reference_share);

// The strict beta0_max up to mu_strict_below, the lenient beta0_min from mu_lenient_above on,
// linear between: a degenerate scene gets the lenient threshold. With the knots at 0 and 1 it is
// the paper's beta0 = mu (beta0_min - beta0_max) + beta0_max.
double beta0_from_mu(double mu, double beta0_min_deg, double beta0_max_deg,
                     double mu_strict_below = 0.0, double mu_lenient_above = 1.0);

}  // namespace adaptive_lego_loam
