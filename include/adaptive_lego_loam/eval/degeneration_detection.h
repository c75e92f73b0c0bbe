#pragma once
// The degenerate flag scored against the simulator's truth. A scan is degenerate when its
// information, once the rotation is marginalised out, fixes some translation direction worse
// than `degenerate_sigma_m` (map_optimization's test, core/pipeline/pipeline.h's
// weakest_direction, with mapping.degenerate_translation_sigma); the truth applies it to the
// true information of the scan's returns (observability.csv).

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace adaptive_lego_loam {

bool truly_degenerate(const Eigen::Matrix<double, 6, 6>& information, double degenerate_sigma_m);

// Counts of the flag against the truth, scan by scan. Precision TP / (TP + FP) is empty when the
// flag is never on, recall TP / (TP + FN) when the truth never is.
struct DetectionScore {
  int true_positives = 0, false_positives = 0, false_negatives = 0, true_negatives = 0;
  std::optional<double> precision, recall;
};

// `truth` and `flagged` one entry per scan, the same scans; std::invalid_argument otherwise.
DetectionScore score_detection(const std::vector<bool>& truth, const std::vector<bool>& flagged);

}  // namespace adaptive_lego_loam
