#include "adaptive_lego_loam/io/progress.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

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

namespace {

double status_field_mb(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(field, 0) == 0) {
      std::istringstream in(line.substr(std::string(field).size()));
      double kilobytes = 0.0;
      in >> kilobytes;
      return kilobytes / 1024.0;
    }
  }
  return 0.0;
}

}  // namespace

double resident_memory_mb() {
  return status_field_mb("VmRSS:");
}
double peak_resident_memory_mb() {
  return status_field_mb("VmHWM:");
}

}  // namespace adaptive_lego_loam
