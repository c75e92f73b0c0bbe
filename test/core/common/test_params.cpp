#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <algorithm>
#include <fstream>
#include <string>

#include "adaptive_lego_loam/core/common/params.h"

using namespace adaptive_lego_loam;

namespace {

std::string error_of(const std::string& yaml) {
  try {
    parse_config(yaml, "test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* kMinimal = "sensor:\n  rows: 16\n  columns: 1800\n";

}  // namespace

TEST(Params, ShippedConfigsLoad) {
  for (const char* name : {"vlp16", "hdl32", "hdl64e", "kitti", "kitti_16rings", "os0_64", "os1_64",
                           "os1_128", "os2_128", "pandar_xt32", "pandar_qt64", "rs_helios_32"}) {
    const std::string path = std::string(CONFIG_DIR) + "/" + name + ".yaml";
    SCOPED_TRACE(path);
    const Config config = load_config(path);
    EXPECT_EQ(static_cast<int>(config.sensor.beam_angles_deg.size()), config.sensor.rows);
    EXPECT_EQ(config.source, path);
  }
  const Config kitti = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  EXPECT_EQ(kitti.sensor.rows, 64);
  EXPECT_EQ(kitti.sensor.row_source, RowSource::kElevation);
  EXPECT_EQ(kitti.sensor.beam_offsets_m.size(), 64u);
  EXPECT_TRUE(kitti.sensor.deskewed);
  const Config thinned = load_config(std::string(CONFIG_DIR) + "/kitti_16rings.yaml");
  ASSERT_EQ(thinned.sensor.ring_to_row.size(), 64u);
  EXPECT_EQ(std::count(thinned.sensor.ring_to_row.begin(), thinned.sensor.ring_to_row.end(), -1),
            48);
}

// Ouster's drivers and the XT32's number rings from the top beam: their configs turn them round.
TEST(Params, TopDownRingsAreTurnedRound) {
  const Config os1 = load_config(std::string(CONFIG_DIR) + "/os1_128.yaml");
  ASSERT_EQ(os1.sensor.ring_to_row.size(), 128u);
  EXPECT_EQ(os1.sensor.ring_to_row.front(), 127);
  EXPECT_EQ(os1.sensor.ring_to_row.back(), 0);
  EXPECT_DOUBLE_EQ(os1.segmentation.ground_row_gap_deg, 1.0);
  EXPECT_DOUBLE_EQ(
      load_config(std::string(CONFIG_DIR) + "/vlp16.yaml").segmentation.ground_row_gap_deg, 0.0);
  const std::string error =
      error_of(std::string(kMinimal) + "segmentation:\n  ground_row_gap_deg: 11\n");
  EXPECT_NE(error.find("segmentation.ground_row_gap_deg = 11 is out of range"), std::string::npos)
      << error;
}

TEST(Params, RingToRowBelowMinusOneIsRejected) {
  const std::string error = error_of(std::string(kMinimal) + "  ring_to_row: [0, -2, 1]\n");
  EXPECT_NE(error.find("sensor.ring_to_row"), std::string::npos) << error;
}

TEST(Params, EvenBeamsFromVerticalLimits) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/vlp16.yaml");
  ASSERT_EQ(config.sensor.beam_angles_deg.size(), 16u);
  EXPECT_DOUBLE_EQ(config.sensor.beam_angles_deg.front(), -15.0);
  EXPECT_DOUBLE_EQ(config.sensor.beam_angles_deg.back(), 15.0);
  EXPECT_DOUBLE_EQ(config.sensor.beam_angles_deg[1], -13.0);
}

TEST(Params, OutOfRangeValueNamesKeyAndRange) {
  const std::string error = error_of("sensor:\n  rows: -3\n");
  EXPECT_NE(error.find("test.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("sensor.rows"), std::string::npos) << error;
  EXPECT_NE(error.find("[1, 512]"), std::string::npos) << error;
  EXPECT_NE(error.find("test.yaml: sensor.rows = -3 is out of range"), std::string::npos) << error;
}

TEST(Params, WrongTypeNamesKey) {
  const std::string error = error_of(std::string(kMinimal) + "segmentation:\n  beta0_deg: steep\n");
  EXPECT_NE(error.find("segmentation.beta0_deg"), std::string::npos) << error;
  EXPECT_NE(error.find("a number"), std::string::npos) << error;
}

TEST(Params, UnknownKeyAndSectionAreErrors) {
  EXPECT_NE(error_of(std::string(kMinimal) + "  colums: 3\n").find("sensor.colums"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "mapping_typo:\n  a: 1\n").find("mapping_typo"),
            std::string::npos);
}

TEST(Params, MissingKeysTakeTheDocumentedDefaultsButTheSensorSectionIsRequired) {
  const Config config =
      parse_config(std::string(kMinimal) + "mapping:\n  keyframe_distance: 2.0\n", "partial.yaml");
  EXPECT_EQ(config.mapping.keyframe_distance, 2.0);
  EXPECT_EQ(config.mapping.keyframe_angle_deg, MappingParams().keyframe_angle_deg);
  EXPECT_EQ(config.loop_closure.min_inlier_ratio, LoopClosureParams().min_inlier_ratio);
  EXPECT_EQ(config.saved_map.voxel_size, SavedMapParams().voxel_size);
  EXPECT_NE(error_of("mapping:\n  keyframe_distance: 2.0\n").find("sensor: missing section"),
            std::string::npos);
}

TEST(Params, BeamTableMustMatchRowsAndAscend) {
  EXPECT_NE(error_of("sensor:\n  rows: 3\n  beam_angles_deg: [-2, 0]\n").find("one per row"),
            std::string::npos);
  EXPECT_NE(error_of("sensor:\n  rows: 3\n  beam_angles_deg: [-2, 1, 0]\n").find("ascending"),
            std::string::npos);
}

TEST(Params, ChoiceListsAllowedValues) {
  const std::string error = error_of(std::string(kMinimal) + "  row_source: laser\n");
  EXPECT_NE(error.find("auto, ring, elevation"), std::string::npos) << error;
}

TEST(Params, Beta0BoundsMustBeOrdered) {
  const std::string error = error_of(std::string(kMinimal) +
                                     "ambient_filter:\n  beta0_min_deg: 50\n  beta0_max_deg: 20\n");
  EXPECT_NE(error.find("ambient_filter.beta0_min_deg"), std::string::npos) << error;
}

TEST(Params, MuKnotsMustBeOrdered) {
  const std::string error = error_of(std::string(kMinimal) +
                                     "ambient_filter:\n  mu_strict_below: 0.6\n"
                                     "  mu_lenient_above: 0.4\n");
  EXPECT_NE(error.find("ambient_filter.mu_strict_below"), std::string::npos) << error;
  EXPECT_NE(error.find("mu_lenient_above"), std::string::npos) << error;
}

TEST(Params, MissingFileAndBrokenYaml) {
  try {
    load_config("/nonexistent/x.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.yaml"), std::string::npos);
  }
  EXPECT_NE(error_of("sensor: [1, 2\n").find("not valid YAML"), std::string::npos);
}

TEST(Params, LoopClosureSection) {
  const Config shipped = load_config(std::string(CONFIG_DIR) + "/vlp16.yaml");
  EXPECT_TRUE(shipped.loop_closure.enabled);
  EXPECT_DOUBLE_EQ(shipped.loop_closure.search_radius, 7.0);
  EXPECT_DOUBLE_EQ(shipped.loop_closure.min_time_gap, 30.0);
  EXPECT_EQ(shipped.loop_closure.neighbourhood_keyframes, 25);
  EXPECT_TRUE(shipped.loop_closure.place.enabled);
  EXPECT_EQ(shipped.loop_closure.place.sectors, 60);
  EXPECT_DOUBLE_EQ(shipped.loop_closure.min_inlier_ratio, 0.95);
  EXPECT_EQ(shipped.loop_closure.consistency_window, 30);
  EXPECT_EQ(shipped.loop_closure.robust_loss, RobustLoss::kCauchy);
  EXPECT_EQ(shipped.loop_closure.map_points_per_scan, 10000);
  EXPECT_EQ(shipped.loop_closure.icp_iterations_per_scan, 1);
  EXPECT_EQ(shipped.loop_closure.graph_iterations_per_scan, 1);

  const Config config = parse_config(std::string(kMinimal) +
                                         "loop_closure:\n  enabled: false\n  search_radius: 12\n"
                                         "  robust_loss: huber\n  robust_loss_scale: 1.5\n"
                                         "  loop_sigma_rotation_deg: 2\n",
                                     "test.yaml");
  EXPECT_FALSE(config.loop_closure.enabled);
  EXPECT_DOUBLE_EQ(config.loop_closure.search_radius, 12.0);
  EXPECT_EQ(config.loop_closure.robust_loss, RobustLoss::kHuber);
  EXPECT_DOUBLE_EQ(config.loop_closure.robust_loss_scale, 1.5);
  EXPECT_DOUBLE_EQ(config.loop_closure.loop_sigma_rotation_deg, 2.0);
  EXPECT_DOUBLE_EQ(config.loop_closure.min_time_gap, LoopClosureParams().min_time_gap);

  const std::string negative_sigma =
      error_of(std::string(kMinimal) + "loop_closure:\n  odometry_sigma_translation: -1\n");
  EXPECT_NE(negative_sigma.find("loop_closure.odometry_sigma_translation"), std::string::npos)
      << negative_sigma;
  EXPECT_NE(error_of(std::string(kMinimal) + "loop_closure:\n  icp_max_iterations: 0\n")
                .find("loop_closure.icp_max_iterations"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "loop_closure:\n  icp_iterations_per_scan: 0\n")
                .find("loop_closure.icp_iterations_per_scan"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "loop_closure:\n  robust_loss: tukey\n")
                .find("cauchy, huber, none"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "loop_closure:\n  search_radus: 5\n")
                .find("loop_closure.search_radus"),
            std::string::npos);
}

TEST(Params, ClusteringBenchmarkMinClusterPoints) {
  const Config kitti = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  EXPECT_EQ(kitti.clustering_benchmark.min_cluster_points, 1);
  const Config set = parse_config(
      std::string(kMinimal) + "clustering_benchmark:\n  min_cluster_points: 30\n", "test.yaml");
  EXPECT_EQ(set.clustering_benchmark.min_cluster_points, 30);
  const std::string zero =
      error_of(std::string(kMinimal) + "clustering_benchmark:\n  min_cluster_points: 0\n");
  EXPECT_NE(zero.find("clustering_benchmark.min_cluster_points"), std::string::npos) << zero;
  EXPECT_NE(zero.find("[1, 1000000]"), std::string::npos) << zero;
  const std::string typo =
      error_of(std::string(kMinimal) + "clustering_benchmark:\n  min_cluster_size: 5\n");
  EXPECT_NE(typo.find("clustering_benchmark.min_cluster_size"), std::string::npos) << typo;
}

TEST(Params, KeyThatIsAListIsAConfigError) {
  // yaml-cpp's own conversion error must not escape: a key must be a name.
  std::string error = error_of(std::string(kMinimal) + "? [x]\n: 1\n");
  EXPECT_NE(error.find("test.yaml: (top level): the key at line 4 is not a name"),
            std::string::npos)
      << error;
  error = error_of("sensor: {rows: 16, [a]: 2}\n");
  EXPECT_NE(error.find("test.yaml: sensor: the key at line 1 is not a name"), std::string::npos)
      << error;
}

TEST(Params, MotionSensorSectionsAreOptionalAndChecked) {
  const Config plain = parse_config(kMinimal, "test.yaml");
  EXPECT_EQ(plain.imu.extrinsic_xyz_m, std::vector<double>({0.0, 0.0, 0.0}));
  const Config mounted = parse_config(
      std::string(kMinimal) +
          "imu:\n  extrinsic_rpy_deg: [180, 0, 90]\n  extrinsic_xyz_m: [0.1, -0.05, -0.2]\n"
          "  time_offset_s: 0.002\nwheel_odometry:\n  extrinsic_xyz_m: [-0.8, 0, -1.73]\n",
      "test.yaml");
  EXPECT_EQ(mounted.imu.extrinsic_rpy_deg, std::vector<double>({180.0, 0.0, 90.0}));
  EXPECT_DOUBLE_EQ(mounted.imu.time_offset_s, 0.002);
  EXPECT_DOUBLE_EQ(mounted.wheel_odometry.extrinsic_xyz_m[2], -1.73);

  std::string error = error_of(std::string(kMinimal) + "imu:\n  extrinsic_xyz_m: [0.1, 0.2]\n");
  EXPECT_NE(error.find("imu.extrinsic_xyz_m: expected a list of three numbers, found 2"),
            std::string::npos)
      << error;
  error = error_of(std::string(kMinimal) + "wheel_odometry:\n  scale: 1.02\n");
  EXPECT_NE(error.find("wheel_odometry.scale: is not a known key"), std::string::npos) << error;
}

TEST(Params, LaterFilesReplaceKeysOfEarlierOnes) {
  const std::string base = std::string(CONFIG_DIR) + "/vlp16.yaml";
  const std::string overlay = ::testing::TempDir() + "/alego_overlay.yaml";
  {
    std::ofstream file(overlay);
    file << "imu:\n  extrinsic_xyz_m: [0.1, 0.2, 0.3]\nmapping:\n  residual_sigma: 0.7\n";
  }
  const Config merged = load_config(std::vector<std::string>{base, overlay});
  EXPECT_EQ(merged.imu.extrinsic_xyz_m, std::vector<double>({0.1, 0.2, 0.3}));
  EXPECT_DOUBLE_EQ(merged.mapping.residual_sigma, 0.7);
  // The rest of each section stays the first file's.
  const Config plain = load_config(base);
  EXPECT_EQ(merged.mapping.max_iterations, plain.mapping.max_iterations);
  EXPECT_DOUBLE_EQ(merged.imu.gyro_noise_density, plain.imu.gyro_noise_density);
  EXPECT_NE(merged.source.find(" + "), std::string::npos);
}

// A config's per-scan settings are given for 0.1 s scans and hold per second at any rate: at
// 20 Hz the motion gate allows half the change per scan and holds twice the scans, mu is smoothed
// with the same time constant; at 10 Hz nothing changes, not by a rounding.
TEST(Params, PerScanSettingsHoldPerSecondAtAnyRate) {
  std::ifstream file(std::string(CONFIG_DIR) + "/vlp16.yaml");
  std::stringstream text;
  text << file.rdbuf();
  const std::string at_10_hz = text.str();
  const auto at_period = [&](const std::string& period) {
    std::string yaml = at_10_hz;
    const std::string key = "  scan_period: 0.1\n";
    yaml.replace(yaml.find(key), key.size(), "  scan_period: " + period + "\n");
    return parse_config(yaml, "vlp16_" + period + ".yaml");
  };
  const Config ten = parse_config(at_10_hz, "vlp16.yaml");
  EXPECT_EQ(ten.mapping.max_motion_change, 0.3);
  EXPECT_EQ(ten.mapping.max_motion_change_deg, 5.0);
  EXPECT_EQ(ten.mapping.max_gated_scans, 3);
  EXPECT_EQ(ten.ambient.mu_smoothing, 0.8);
  EXPECT_EQ(ten.localization.lost_after_scans, 5);
  const Config twenty = at_period("0.05");
  EXPECT_DOUBLE_EQ(twenty.mapping.max_motion_change, 0.15);
  EXPECT_DOUBLE_EQ(twenty.mapping.max_motion_change_deg, 2.5);
  EXPECT_EQ(twenty.mapping.max_gated_scans, 6);
  EXPECT_EQ(twenty.localization.lost_after_scans, 10);
  EXPECT_DOUBLE_EQ(twenty.ambient.mu_smoothing * twenty.ambient.mu_smoothing, 0.8);
  const Config five = at_period("0.2");
  EXPECT_DOUBLE_EQ(five.mapping.max_motion_change, 0.6);
  EXPECT_EQ(five.mapping.max_gated_scans, 2);  // 1.5 rounded
  EXPECT_EQ(five.localization.lost_after_scans, 3);
  EXPECT_DOUBLE_EQ(five.ambient.mu_smoothing, 0.64);
}
