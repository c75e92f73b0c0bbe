#pragma once
// A run's degenerate flag and published covariance against a simulated sequence's truth
// (docs/METHOD.md, "Scoring the degeneration"): the flag scan by scan against the truth's
// (degeneration_detection.h), and the NEES of each matched scan's scan-to-scan translation error
// against its covariance (covariance_consistency.h).
//
// Why that error: the published covariance is the scan-to-map match's, of the scan's pose
// relative to the map, not of its drift from the start (which the map's own error carries and
// no covariance here describes). The change of the error over one scan is the nearest measurable
// thing: it is the scan's error relative to the map when the previous scan sat right on the map.
// It also carries the previous scan's error relative to the map where that did not carry over
// into the map, so an exactly consistent covariance can show up to twice the chi-square's NEES.
// Only the translation (3 DOF) is scored: the flag is about it, and it is what degenerates.
// Runs without the covariance are scored along their weakest direction alone (1 DOF: the error
// along it against its sigma).

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/eval/covariance_consistency.h"
#include "adaptive_lego_loam/eval/degeneration_detection.h"
#include "adaptive_lego_loam/eval/degeneration_file.h"
#include "adaptive_lego_loam/eval/observability_file.h"

namespace adaptive_lego_loam {

struct DegenerationEvaluation {
  FlagSource flag_source = FlagSource::kPublished;
  UncertaintySource uncertainty_source = UncertaintySource::kCovariance;
  double degenerate_sigma_m = 0.0;  // the threshold the flags were made with
  int scans_compared = 0;           // in both files (and matched, when the run says)
  int truly_degenerate = 0;
  int flagged = 0;
  DetectionScore detection;
  NeesSummary nees;
};

// `estimate` and `ground_truth`: the run's poses and the true ones, sensor frame, index = scan.
DegenerationEvaluation evaluate_degeneration(const std::vector<TrueObservability>& truth,
                                             const RunDegeneration& run,
                                             const std::vector<Eigen::Isometry3d>& estimate,
                                             const std::vector<Eigen::Isometry3d>& ground_truth,
                                             double degenerate_sigma_m);

}  // namespace adaptive_lego_loam
