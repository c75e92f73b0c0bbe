#pragma once
// The degenerate state reported to users (diagnostics, degeneration.csv), with hysteresis: a scan
// whose weakest direction is known worse than the threshold makes it degenerate at once; it is
// constrained again only after `recover_scans` scans in a row known better than `recover_share`
// of the threshold. A sigma hovering about the threshold then does not toggle a WARN scan after
// scan. (The priors act on each scan's own flag: a prior must hold the scan that needs it.)

namespace adaptive_lego_loam {

class DegeneracyTracker {
 public:
  explicit DegeneracyTracker(double threshold, double recover_share = 0.7, int recover_scans = 5);
  // This scan's weakest sigma (infinite: unknown); returns the state after it.
  bool update(double sigma);
  bool degenerate() const { return degenerate_; }
  void reset();

 private:
  double threshold_, recover_threshold_;
  int recover_scans_;
  bool degenerate_ = false;
  int constrained_in_a_row_ = 0;
};

}  // namespace adaptive_lego_loam
