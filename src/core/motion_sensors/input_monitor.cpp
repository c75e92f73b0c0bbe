#include "adaptive_lego_loam/core/motion_sensors/input_monitor.h"

#include <cmath>

namespace adaptive_lego_loam {

const char* to_string(SampleFault fault) {
  switch (fault) {
    case SampleFault::kNotFinite:
      return "not finite";
    case SampleFault::kOutOfOrder:
      return "out of order";
    case SampleFault::kRepeatedStamp:
      return "repeated stamp";
    case SampleFault::kBeyondLimits:
      return "beyond limits";
  }
  return "unknown";
}

long InputStatus::dropped() const {
  long sum = 0;
  for (long count : faults)
    sum += count;
  return sum;
}

std::optional<SampleFault> InputMonitor::check(double stamp, bool finite, bool plausible) {
  std::optional<SampleFault> fault;
  const bool started = !std::isnan(status_.last_stamp);
  if (!finite || !std::isfinite(stamp)) {
    fault = SampleFault::kNotFinite;
  } else if (started && stamp < status_.last_stamp) {
    fault = SampleFault::kOutOfOrder;
  } else if (started && stamp == status_.last_stamp) {
    fault = SampleFault::kRepeatedStamp;
  } else if (!plausible) {
    fault = SampleFault::kBeyondLimits;
  }
  if (fault) {
    ++status_.faults[static_cast<int>(*fault)];
    return fault;
  }
  if (started) {
    const double interval = stamp - status_.last_stamp;
    if (interval > max_gap_s_) {
      ++status_.gaps;
      status_.latest_gap_s = interval;
    } else {
      // The rate over about the newest 20 samples; a gap does not count as a slow sample.
      constexpr double kWeight = 0.05;
      mean_interval_ =
          mean_interval_ > 0.0 ? (1.0 - kWeight) * mean_interval_ + kWeight * interval : interval;
      status_.rate_hz = 1.0 / mean_interval_;
    }
  }
  status_.last_stamp = stamp;
  ++status_.accepted;
  return std::nullopt;
}

}  // namespace adaptive_lego_loam
