#pragma once
// The health of one optional input's sample stream: which samples are faults (dropped and counted,
// never used), the rate, and the gaps. A fault is reported once per kind to whoever logs it.

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

namespace adaptive_lego_loam {

enum class SampleFault { kNotFinite, kOutOfOrder, kRepeatedStamp, kBeyondLimits };
constexpr int kSampleFaultKinds = 4;
// "not finite", "out of order", "repeated stamp", "beyond limits"
const char* to_string(SampleFault fault);

struct InputStatus {
  long accepted = 0;
  std::array<long, kSampleFaultKinds> faults{};  // dropped samples, by kind
  long gaps = 0;                                 // intervals longer than the input's max gap
  double last_stamp = std::numeric_limits<double>::quiet_NaN();  // of the newest accepted sample
  double latest_gap_s = 0.0;  // the newest gap's length (0: none yet)
  double rate_hz = 0.0;       // over the newest samples (0: fewer than two yet)
  long dropped() const;
};

class InputMonitor {
 public:
  // Intervals longer than `max_gap_s` are gaps.
  explicit InputMonitor(double max_gap_s) : max_gap_s_(max_gap_s) {}
  // Checks a sample at `stamp` whose values are `finite` and within the input's limits
  // (`plausible`): nothing when it is accepted, else the fault it was dropped for.
  std::optional<SampleFault> check(double stamp, bool finite, bool plausible);
  const InputStatus& status() const { return status_; }

 private:
  double max_gap_s_;
  InputStatus status_;
  double mean_interval_ = 0.0;
};

// Whether samples (ordered by stamp) cover [from, to] without a gap: the last one at or before
// `from`, those between and `to` each within `max_gap` of the next. Only samples up to `to` count,
// so the answer does not depend on when later ones arrive.
template <class Samples>
bool samples_cover(const Samples& samples, double from, double to, double max_gap) {
  double last = -std::numeric_limits<double>::infinity();
  for (const auto& sample : samples) {
    if (sample.stamp > to) break;
    if (sample.stamp > from && sample.stamp - std::max(last, from) > max_gap) return false;
    last = sample.stamp;
  }
  return last > -std::numeric_limits<double>::infinity() && to - std::max(last, from) <= max_gap;
}

}  // namespace adaptive_lego_loam
