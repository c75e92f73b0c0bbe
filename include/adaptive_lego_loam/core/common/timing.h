#pragma once
// Per-stage wall-clock times. Every stage of the pipeline reports into one of these so the
// offline runner, the nodes and the benchmarks print the same figures.

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

enum class Clock { kWall, kThreadCpu };

// The clock of the Stopwatches made afterwards without one; wall-clock by default. Thread CPU
// time leaves out the time other processes held the core: stage times on a shared machine.
void set_stage_clock(Clock clock);

class Stopwatch {
 public:
  Stopwatch();  // on the stage clock
  explicit Stopwatch(Clock clock) : clock_(clock), start_(now_ms(clock)) {}
  double elapsed_ms() const { return now_ms(clock_) - start_; }
  // Returns the time since the last lap (or construction) and starts a new lap.
  double lap_ms() {
    const double now = now_ms(clock_);
    const double ms = now - start_;
    start_ = now;
    return ms;
  }

 private:
  static double now_ms(Clock clock);
  Clock clock_;
  double start_;
};

}  // namespace adaptive_lego_loam
