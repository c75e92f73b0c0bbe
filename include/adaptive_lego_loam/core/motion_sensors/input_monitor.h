#pragma once
// The health of one optional input's sample stream: which samples are faults (dropped and counted,
// never used), the rate, and the gaps. A fault is reported once per kind to whoever logs it.

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
  // Whether the samples cover (from, to]: no gap ended after `from`, and the newest sample is at
  // most a max gap before `to`.
  bool covers(double from, double to) const;

 private:
  double max_gap_s_;
  InputStatus status_;
  double mean_interval_ = 0.0;
  double last_gap_end_ = -std::numeric_limits<double>::infinity();
};

}  // namespace adaptive_lego_loam
