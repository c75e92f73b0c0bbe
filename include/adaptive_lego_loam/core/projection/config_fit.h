#pragma once
// Whether a sensor config fits the clouds it is given (docs/SENSORS.md): a wrong number of rows,
// beam table or column count projects a scan without an error and tracks badly without a word.

#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

// What one projected scan says about the config.
struct ConfigFit {
  bool rows_from_ring = false;
  // Points at least kMinCheckRange away (horizontally), and of those the points off their row's
  // beam: rows from the ring field, farther than half the row spacing (it belongs to another
  // beam) plus the angle kOriginSlack makes at its range (a driver's frame a few centimetres off
  // the beams' centre); rows from the elevation, which puts every point within half, farther
  // than a fifth.
  int checked = 0;
  int off_beam = 0;
  int rows = 0, columns = 0;
  int empty_inner_rows = 0;  // without a point, between rows with points
  int projected = 0;
  int without_cell = 0;  // lost for lack of a free column: more returns per turn than columns
  int outside_rows = 0;  // ring beyond the rows, or elevation beyond the beams

  static constexpr double kMinCheckRange = 2.0;  // m
  static constexpr double kOriginSlack = 0.05;   // m
  static constexpr int kMinChecked = 500;

  // One line per thing that does not fit (none when the config fits).
  std::vector<std::string> problems() const;
};

ConfigFit check_config_fit(const SensorParams& sensor, const RangeImage& image,
                           bool rows_from_ring);

// Whether the projection took a cloud's rows from its ring field (see RowSource).
inline bool rows_from_ring(const SensorParams& sensor, bool cloud_has_ring) {
  return sensor.row_source == RowSource::kRing ||
         (sensor.row_source == RowSource::kAuto && cloud_has_ring);
}

// Whether `config` reads the scans of a sensor whose geometry is `sensor` (its beams, their
// origins, its ring numbering) firing `firings` times a turn: rows from a ring field (when the
// scans have one and the config takes it) need the same rows and rings; rows from the elevation
// the same beams within 0.01 deg and origins within 5 mm. Either way the beams within 0.05 deg, at
// least as many columns as firings (at most 10 % more) and the same scan period.
bool config_reads(const SensorParams& config, const SensorParams& sensor, int firings,
                  bool ring_field);

// Says what does not fit once: the first scan with a problem gives the line to log (naming the
// config, the input and derive_config), later scans nothing. It looks at each of the first 20
// scans, then at every 20th.
class ConfigFitWarning {
 public:
  ConfigFitWarning(std::string config, std::string input)
      : config_(std::move(config)), input_(std::move(input)) {}
  std::optional<std::string> check(const SensorParams& sensor, const RangeImage& image,
                                   bool rows_from_ring);
  // Every problem seen so far, once each (for a run's summary).
  const std::vector<std::string>& seen() const { return seen_; }

 private:
  std::string config_, input_;
  bool warned_ = false;
  long scans_ = 0;
  std::vector<std::string> seen_;
};

}  // namespace adaptive_lego_loam
