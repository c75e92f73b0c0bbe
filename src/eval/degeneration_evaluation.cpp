#include "adaptive_lego_loam/eval/degeneration_evaluation.h"

#include <map>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam {
namespace {

using Poses = std::vector<Eigen::Isometry3d>;

// Against the translation's covariance (3 DOF), or along the weakest direction against its sigma
// (1 DOF; an infinite sigma claims nothing: NEES 0).
double scan_nees(const RunScan& scan, const Eigen::Vector3d& error) {
  if (scan.translation_covariance) {
    try {
      return nees(error, *scan.translation_covariance);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("frame " + std::to_string(scan.frame) + ": " + e.what());
    }
  }
  const double along = error.dot(scan.weak_direction) / scan.weak_sigma_m;
  return along * along;
}

bool has_poses(const Poses& estimate, const Poses& ground_truth, int frame) {
  const std::size_t needed = static_cast<std::size_t>(frame) + 1;
  return frame >= 1 && estimate.size() >= needed && ground_truth.size() >= needed;
}

}  // namespace

DegenerationEvaluation evaluate_degeneration(const std::vector<TrueObservability>& truth,
                                             const RunDegeneration& run, const Poses& estimate,
                                             const Poses& ground_truth, double degenerate_sigma_m) {
  std::map<int, const Eigen::Matrix<double, 6, 6>*> true_information;
  for (const TrueObservability& scan : truth)
    true_information[scan.frame] = &scan.information;
  DegenerationEvaluation evaluation;
  evaluation.flag_source = run.flag_source;
  evaluation.uncertainty_source = run.uncertainty_source;
  evaluation.degenerate_sigma_m = degenerate_sigma_m;
  std::vector<bool> true_flags, run_flags;
  std::vector<double> values;
  for (const RunScan& scan : run.scans) {
    const auto found = true_information.find(scan.frame);
    if (found == true_information.end() || scan.matched == false) continue;
    true_flags.push_back(truly_degenerate(*found->second, degenerate_sigma_m));
    run_flags.push_back(scan.degenerate);
    if (!has_poses(estimate, ground_truth, scan.frame)) continue;
    const Eigen::Vector3d error =
        increment_translation_error(estimate[scan.frame - 1], estimate[scan.frame],
                                    ground_truth[scan.frame - 1], ground_truth[scan.frame]);
    values.push_back(scan_nees(scan, error));
  }
  evaluation.scans_compared = static_cast<int>(true_flags.size());
  for (std::size_t i = 0; i < true_flags.size(); ++i) {
    evaluation.truly_degenerate += true_flags[i];
    evaluation.flagged += run_flags[i];
  }
  evaluation.detection = score_detection(true_flags, run_flags);
  evaluation.nees =
      summarize_nees(values, run.uncertainty_source == UncertaintySource::kCovariance ? 3 : 1);
  return evaluation;
}

}  // namespace adaptive_lego_loam
