#pragma once
// Per-stage wall-clock times. Every stage of the pipeline reports into one of these so the
// offline runner, the nodes and the benchmarks print the same figures.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace adaptive_lego_loam {

class StageTimes {
 public:
  void add(const std::string& stage, double ms);
  double get(const std::string& stage) const;  // 0 when the stage did not run
  double total() const;
  const std::vector<std::pair<std::string, double>>& entries() const { return entries_; }
  void clear() { entries_.clear(); }
  void append(const StageTimes& other);

 private:
  std::vector<std::pair<std::string, double>> entries_;
};

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }
  // Returns the time since the last lap (or construction) and starts a new lap.
  double lap_ms() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace adaptive_lego_loam
