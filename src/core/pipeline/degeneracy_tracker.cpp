#include "adaptive_lego_loam/core/pipeline/degeneracy_tracker.h"

namespace adaptive_lego_loam {

DegeneracyTracker::DegeneracyTracker(double threshold, double recover_share, int recover_scans)
    : threshold_(threshold),
      recover_threshold_(threshold * recover_share),
      recover_scans_(recover_scans) {}

bool DegeneracyTracker::update(double sigma) {
  if (!(sigma <= threshold_)) {
    degenerate_ = true;
    constrained_in_a_row_ = 0;
    return degenerate_;
  }
  constrained_in_a_row_ = sigma < recover_threshold_ ? constrained_in_a_row_ + 1 : 0;
  if (constrained_in_a_row_ >= recover_scans_) degenerate_ = false;
  return degenerate_;
}

void DegeneracyTracker::reset() {
  degenerate_ = false;
  constrained_in_a_row_ = 0;
}

}  // namespace adaptive_lego_loam
