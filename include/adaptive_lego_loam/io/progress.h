#pragma once
// A progress bar for long-running tools, drawn on stderr only when stderr is a terminal.

#include <string>

#include "adaptive_lego_loam/core/common/timing.h"

namespace adaptive_lego_loam {

class ProgressBar {
 public:
  // `total` < 0 when unknown.
  ProgressBar(std::string label, int total);
  void update(int done);
  void finish();

 private:
  std::string label_;
  int total_;
  bool enabled_;
  Stopwatch watch_;
  double last_draw_ms_ = -1e9;
};

}  // namespace adaptive_lego_loam
