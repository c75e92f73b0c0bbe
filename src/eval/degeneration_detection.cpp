#include "adaptive_lego_loam/eval/degeneration_detection.h"

#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/odometry/observability.h"

namespace adaptive_lego_loam {

bool truly_degenerate(const Eigen::Matrix<double, 6, 6>& information, double degenerate_sigma_m) {
  return !(observability(information).weakest_sigma() <= degenerate_sigma_m);
}

DetectionScore score_detection(const std::vector<bool>& truth, const std::vector<bool>& flagged) {
  if (truth.size() != flagged.size()) {
    throw std::invalid_argument("score_detection: " + std::to_string(truth.size()) +
                                " true flags but " + std::to_string(flagged.size()) +
                                " estimated ones");
  }
  DetectionScore score;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i]) {
      ++(flagged[i] ? score.true_positives : score.false_negatives);
    } else {
      ++(flagged[i] ? score.false_positives : score.true_negatives);
    }
  }
  const int flagged_count = score.true_positives + score.false_positives;
  const int true_count = score.true_positives + score.false_negatives;
  if (flagged_count > 0) score.precision = double(score.true_positives) / flagged_count;
  if (true_count > 0) score.recall = double(score.true_positives) / true_count;
  return score;
}

}  // namespace adaptive_lego_loam
