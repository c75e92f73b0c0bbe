#include "adaptive_lego_loam/io/progress.h"

#include <unistd.h>

#include <cstdio>

namespace adaptive_lego_loam {

ProgressBar::ProgressBar(std::string label, int total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) == 1) {}

void ProgressBar::update(int done) {
  if (!enabled_) return;
  const double now = watch_.elapsed_ms();
  if (now - last_draw_ms_ < 100.0 && done != total_) return;
  last_draw_ms_ = now;
  const double rate = now > 0 ? done / (now / 1000.0) : 0.0;
  constexpr int kWidth = 30;
  std::string bar;
  if (total_ > 0) {
    const int filled = static_cast<int>(kWidth * double(done) / total_);
    bar = "[" + std::string(filled, '=') + std::string(kWidth - filled, ' ') + "] ";
  }
  std::fprintf(stderr, "\r%s %s%d%s frames, %.1f frames/s ", label_.c_str(), bar.c_str(), done,
               total_ > 0 ? ("/" + std::to_string(total_)).c_str() : "", rate);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

}  // namespace adaptive_lego_loam
