#pragma once
// The stamps of a scan stream against the sensor's period: the next scan, a gap (scans missing:
// the driver or a stage fell behind, or the recording paused), a duplicate, or a jump back in time
// (a bag played again in a loop).

namespace adaptive_lego_loam {

enum class StampStep { kFirst, kNext, kGap, kDuplicate, kBackward };
const char* to_string(StampStep step);

class ScanStamps {
 public:
  // `scan_period` > 0 (s).
  explicit ScanStamps(double scan_period) : period_(scan_period) {}
  // Classifies `stamp` against the last one and makes it the last (a duplicate changes nothing).
  // More than 1.5 periods after the last is a gap; within a hundredth of a period, a duplicate.
  // Throws std::invalid_argument on a stamp that is not finite.
  StampStep add(double stamp);
  // Scans missing in the gaps so far: each gap's length in periods, rounded, less one.
  long missing() const { return missing_; }
  int gaps() const { return gaps_; }
  int duplicates() const { return duplicates_; }
  int backward_jumps() const { return backward_; }
  // The last gap's length (s).
  double last_gap() const { return last_gap_; }

 private:
  double period_;
  bool started_ = false;
  double last_ = 0.0;
  long missing_ = 0;
  int gaps_ = 0, duplicates_ = 0, backward_ = 0;
  double last_gap_ = 0.0;
};

}  // namespace adaptive_lego_loam
