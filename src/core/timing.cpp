#include "adaptive_lego_loam/core/timing.h"

namespace adaptive_lego_loam {

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
