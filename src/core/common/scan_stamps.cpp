#include "adaptive_lego_loam/core/common/scan_stamps.h"

#include <cmath>
#include <stdexcept>

namespace adaptive_lego_loam {

const char* to_string(StampStep step) {
  switch (step) {
    case StampStep::kFirst:
      return "first";
    case StampStep::kNext:
      return "next";
    case StampStep::kGap:
      return "gap";
    case StampStep::kDuplicate:
      return "duplicate";
    case StampStep::kBackward:
      return "backward";
  }
  return "unknown";
}

StampStep ScanStamps::add(double stamp) {
  if (!std::isfinite(stamp)) throw std::invalid_argument("scan stamp is not a finite number");
  if (!started_) {
    started_ = true;
    last_ = stamp;
    return StampStep::kFirst;
  }
  const double step = stamp - last_;
  if (std::abs(step) <= 0.01 * period_) {
    ++duplicates_;
    return StampStep::kDuplicate;
  }
  last_ = stamp;
  if (step < 0.0) {
    ++backward_;
    return StampStep::kBackward;
  }
  if (step <= 1.5 * period_) return StampStep::kNext;
  ++gaps_;
  last_gap_ = step;
  missing_ += std::lround(step / period_) - 1;
  return StampStep::kGap;
}

}  // namespace adaptive_lego_loam
