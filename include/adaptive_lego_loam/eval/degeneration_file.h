#pragma once
// What run_sequence's degeneration.csv says of each scan's degeneration and of the pose's
// uncertainty, read by column name. Runs from before the columns `lidar_weak_sigma_m,degenerate,
// matched,covariance_00..covariance_55` existed are read as far as they go (the sources say
// what was used):
//   flag:        `degenerate` (map_optimization's flag: the correspondences' information, along
//                the ambient filter's weak direction counted as 1 - mu, fixes a translation worse
//                than the threshold), else `map_weak_sigma_m` beyond the threshold (the
//                correspondences' information without the scene's discount)
//   uncertainty: the published pose covariance (`covariance_rc`), else the weakest direction
//                and sigma of the estimate's information (`estimate_weak_*`: of the same
//                covariance), else of the correspondences' (`map_weak_*`).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace adaptive_lego_loam {

enum class FlagSource { kPublished, kCorrespondences };
enum class UncertaintySource { kCovariance, kEstimateWeakest, kCorrespondenceWeakest };
const char* to_string(FlagSource source);
const char* to_string(UncertaintySource source);

struct RunScan {
  int frame = 0;
  bool degenerate = false;
  // Whether the scan matched the map (unmatched: its pose is the guess): the run's `matched`, or
  // in an older run, whether its correspondences fixed anything (map_weak_sigma_m and
  // map_rotation_sigma_deg not both inf); empty when neither is there.
  std::optional<bool> matched;
  // The translation's marginal covariance (m^2, sensor frame) with kCovariance; otherwise the
  // direction of its largest variance and its sigma (m, inf when nothing fixes it).
  std::optional<Eigen::Matrix3d> translation_covariance;
  Eigen::Vector3d weak_direction = Eigen::Vector3d::UnitX();
  double weak_sigma_m = 0.0;
};

struct RunDegeneration {
  FlagSource flag_source = FlagSource::kPublished;
  UncertaintySource uncertainty_source = UncertaintySource::kCovariance;
  std::vector<RunScan> scans;
};

// `degenerate_sigma_m` (mapping.degenerate_translation_sigma) makes the flag of a run without the
// `degenerate` column. Throws IoError "<path>:<line>: ..." on bad rows and when neither source of
// a flag or of the uncertainty is there.
RunDegeneration read_degeneration_csv(const std::string& path, double degenerate_sigma_m);
RunDegeneration parse_degeneration_csv(const std::string& text, const std::string& source,
                                       double degenerate_sigma_m);

}  // namespace adaptive_lego_loam
