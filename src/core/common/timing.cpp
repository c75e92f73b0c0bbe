#include "adaptive_lego_loam/core/common/timing.h"

#include <chrono>
#include <ctime>

namespace adaptive_lego_loam {
namespace {
Clock stage_clock = Clock::kWall;
}  // namespace

void set_stage_clock(Clock clock) {
  stage_clock = clock;
}

Stopwatch::Stopwatch() : Stopwatch(stage_clock) {}

double Stopwatch::now_ms(Clock clock) {
  if (clock == Clock::kThreadCpu) {
    timespec now;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return now.tv_sec * 1e3 + now.tv_nsec * 1e-6;
  }
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void StageTimes::add(const std::string& stage, double ms) {
  for (auto& entry : entries_) {
    if (entry.first == stage) {
      entry.second += ms;
      return;
    }
  }
  entries_.emplace_back(stage, ms);
}

double StageTimes::get(const std::string& stage) const {
  for (const auto& entry : entries_) {
    if (entry.first == stage) return entry.second;
  }
  return 0.0;
}

double StageTimes::total() const {
  double sum = 0.0;
  for (const auto& entry : entries_)
    sum += entry.second;
  return sum;
}

void StageTimes::append(const StageTimes& other) {
  for (const auto& entry : other.entries_)
    add(entry.first, entry.second);
}

}  // namespace adaptive_lego_loam
