#pragma once
// One params struct per stage, filled from one YAML file per sensor (config/*.yaml).
// No sensor constant is compiled in: the defaults below only fill keys a file leaves out.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace adaptive_lego_loam {

// A config value that is missing, malformed or out of range. The message names the file, the
// key and what was expected.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class RowSource { kAuto, kRing, kElevation };

// The sensor period a config's per-scan settings are given for (s). At another period
// parse_config scales them so that they hold per second: the motion gate's change per scan
// (mapping.max_motion_change, max_motion_change_deg) in proportion, the scans it may hold
// (max_gated_scans) and localization's lost_after_scans inversely, ambient_filter.mu_smoothing
// to the same time constant (s^(period / 0.1)).
constexpr double kReferenceScanPeriod = 0.1;

struct SensorParams {
  std::string name = "unnamed";
  int rows = 16;
  int columns = 1800;
  // kAuto: the ring field when the cloud has one, else the elevation angle.
  RowSource row_source = RowSource::kAuto;
  // Elevation of each row, ascending (row 0 = lowest beam), degrees. Filled from
  // beam_angles_deg, or spread evenly over [vertical_min_deg, vertical_max_deg].
  std::vector<double> beam_angles_deg;
  // Height of each beam's origin above the sensor origin (m). The HDL-64E's two laser blocks sit
  // about 0.2 m and 0.12 m above its origin; without this the elevation of a beam drifts with
  // range by more than the row spacing. Zero when not given.
  std::vector<double> beam_offsets_m;
  // ring value -> row, when the driver does not number rings bottom-up; -1 leaves the ring out (a
  // dead laser, or KITTI's 64 rings thinned to a VLP-16-sized 16). Identity when empty.
  std::vector<int> ring_to_row;
  double min_range = 1.0;    // m
  double max_range = 100.0;  // m
  double mount_angle_deg = 0.0;
  int ground_rows = 7;       // rows counted from the bottom that may hold ground
  double scan_period = 0.1;  // s
  bool deskewed = false;     // true when the driver already removed motion distortion (KITTI)
};

// Minimum size for a cluster to be kept, as LeGO-LOAM: at least min_points, or at least
// min_points_multi_row spanning at least min_rows rows.
struct ClusterSizeRule {
  int min_points = 30;
  int min_points_multi_row = 5;
  int min_rows = 3;
};

struct SegmentationParams {
  double beta0_deg = 60.0;  // LeGO-LOAM's segmentTheta
  ClusterSizeRule size_rule;
  double ground_slope_tolerance_deg = 10.0;
  // The ground test pairs each row with the first at least this much higher (0: the next row).
  double ground_row_gap_deg = 0.0;
  int ground_downsample = 5;   // keep every n-th ground column in the segmented cloud
  int outlier_downsample = 5;  // keep every n-th outlier column in the outlier cloud
};

// kNone: no segmentation at all, every non-ground point kept (LOAM-like, the paper's baseline).
enum class Beta0Mode { kAdaptive, kFixed, kNone };
const char* to_string(Beta0Mode mode);  // "adaptive", "fixed", "none"

// The adaptive Euclidean join test (docs/METHOD.md step 4): the paper's text compares the 3-D
// distance, |AB| < gamma sin(alpha) |OB|; the authors' published code the range difference,
// |r_A - r_B| < gamma alpha r_A.
enum class EuclideanCriterion { kDistance, kRangeDifference };
const char* to_string(EuclideanCriterion criterion);  // "distance", "range_difference"

struct AmbientFilterParams {
  Beta0Mode mode = Beta0Mode::kAdaptive;
  double beta0_min_deg = 10.0;  // lenient end, for a degenerate scene
  double beta0_max_deg = 60.0;  // strict end, for a well-constrained one
  // Step 8's knots: beta0_max up to mu_strict_below, beta0_min from mu_lenient_above on, linear
  // between (0 and 1: the paper's linear map).
  double mu_strict_below = 0.0;
  double mu_lenient_above = 1.0;
  double skeleton_beta0_deg = 60.0;  // step 5: the skeleton's strict depth clusters
  double fixed_beta0_deg = 60.0;     // used when mode is kFixed
  // Step 4: adaptive Euclidean clustering on the range image.
  int euclidean_window = 5;  // w: the window is (2w+1) x (2w+1)
  double euclidean_gamma = 1.2;
  double euclidean_fixed_threshold = 0.0;  // m; > 0 turns the adaptive threshold off (baseline)
  EuclideanCriterion euclidean_criterion = EuclideanCriterion::kRangeDifference;
  // Step 5: skeleton.
  int skeleton_euclidean_min_points = 100;  // n_e
  int skeleton_depth_min_points = 30;       // n_d
  // Step 6: normals.
  double normal_sample_ratio = 0.1;  // p
  int normal_window = 3;
  double normal_depth_threshold = 1.0;  // depth_0, m
  int normal_min_neighbors = 5;         // t_0
  uint32_t seed = 1;
  // Step 7: below this many skeleton normals mu is pulled toward 1 in proportion; 0 = never.
  int mu_evidence_normals = 0;
  // Step 7: mu shifted by weight * (structure share - reference share); weight 0 = never.
  double mu_structure_weight = 0.0;
  double mu_structure_reference = 0.3;
  // Step 7: fragments smoother than the floor count as structure in proportion; 1 = never.
  double fragment_smoothness_floor = 1.0;
  double fragment_smooth_tolerance_m = 0.05;  // second difference of range along a row
  // Step 8: exponential smoothing of mu over scans; 0 = none. A file gives it for 0.1 s scans
  // (kReferenceScanPeriod).
  double mu_smoothing = 0.0;
  // Step 9: from this mu on every cluster is kept however small, as with kNone; above 1 = never.
  double mu_keep_every_cluster = 2.0;
};

// LeGO-LOAM's feature extraction on the segmented cloud.
struct FeatureParams {
  int sectors = 6;  // each row is split into this many sectors
  int sharp_per_sector = 2;
  int less_sharp_per_sector = 20;
  int flat_per_sector = 4;
  double edge_threshold = 0.1;       // curvature above: edge candidate
  double surface_threshold = 0.1;    // curvature below: surface candidate
  double occlusion_threshold = 0.3;  // m: range step that marks an occluded side
  double parallel_threshold = 0.02;  // relative range step on both sides: beam near parallel
  double less_flat_voxel = 0.2;      // m: voxel filter of the less-flat surfaces per row
};

enum class OdometryMode { kTwoStep, kJoint };

// Scan-to-scan odometry (LeGO-LOAM's featureAssociation).
struct OdometryParams {
  OdometryMode mode = OdometryMode::kJoint;
  int max_iterations = 8;           // correspondence searches per scan
  int solver_iterations = 5;        // Ceres iterations per search
  double max_match_distance = 5.0;  // m
  double huber_loss = 0.1;          // m
  bool constant_velocity = true;    // initial guess from the previous motion
  // De-skew and predict with the previous motion as mapping refined it, when mapping runs.
  bool motion_from_mapping = true;
  // A start in motion (a bag, a node restarted at speed): the first pair of scans is registered
  // from guesses every start_search_step along the sensor's x axis up to start_search_max_speed,
  // and the result that lays most non-ground points onto the first scan is kept
  // (core/odometry/start_search.h); from zero alone it would settle on the nearest alias of a
  // repeating structure (guard-rail posts). 0: from zero alone.
  double start_search_max_speed = 40.0;  // m/s
  double start_search_step = 0.5;        // m
  // A registered motion that is not finite, faster than max_speed or turning faster than
  // max_turn_rate_deg is a registration that ran away, not the vehicle: the scan keeps the
  // predicted motion instead. 0: no bound.
  double max_speed = 50.0;           // m/s
  double max_turn_rate_deg = 360.0;  // deg/s
  // > 0: each scan-to-scan correspondence weighs by the surface its point stands for (range^2)
  // over its expected squared error: range_weight_noise^2 plus (range_weight_fit_error x the ring
  // spacing at its range)^2, relative to a point 10 m away. A car keeping pace close beside the
  // sensor then cannot outvote the scene. 0: every correspondence weighs the same.
  double range_weight_fit_error = 0.0;
  double range_weight_noise = 0.02;  // m
  // The 1-sigma error of a scan-to-scan residual (m): the information of the registration and the
  // covariance of the odometry's pose (MappingParams::residual_sigma's counterpart).
  double residual_sigma = 0.4;
  // > 0: the follow test (m). Each scan is registered a second time from its guess moved this far
  // along the guessed direction of travel; where the result moves with the guess by more than
  // follow_test_max of the shift, the scan does not fix the motion along that direction (a smooth
  // tunnel, whose rings and edges stay where they are in the sensor frame and pull the motion
  // toward standing still), and the motion along it is kept at the guess, by scan-to-scan and by
  // scan-to-map. 0: off.
  double follow_test_shift = 0.0;
  double follow_test_max = 0.5;
  // m/s: a scan that passes the follow test but slows down (its result short of the guess) while
  // the guess is slower than this is registered a third time, from standing still; where that
  // ends more than follow_test_max of the guessed travel short of the result, the result follows
  // its start (a tunnel where the pull toward standing still is as strong as the shift) and is
  // held. 0: no third registration.
  double follow_test_still_speed = 10.0;
};

// Scan-to-map matching and keyframes (LeGO-LOAM's mapOptimization).
struct MappingParams {
  bool enabled = true;
  int max_iterations = 10;
  int solver_iterations = 4;
  // m: a scan point that moved less than this since its neighbour search keeps its line or plane
  // (0: search again whenever the neighbours may have changed, the same result as always
  // searching).
  double keep_correspondence_distance = 0.0;
  double huber_loss = 0.1;           // m
  double corner_voxel = 0.2;         // m, local map and current corners
  double surface_voxel = 0.4;        // m, local map surfaces
  double scan_corner_voxel = 0.2;    // m, the current scan's edges matched against the map
  double scan_surface_voxel = 0.4;   // m, the current scan's surfaces matched against the map
  double keyframe_distance = 1.0;    // m between keyframes ...
  double keyframe_angle_deg = 10.0;  // ... or this much rotation
  double local_map_radius = 50.0;    // m: keyframes within this distance form the local map
  int local_map_keyframes = 40;      // at most this many, nearest in time first
  // The newest keyframes left out of the local map: matched against its own last few metres, a
  // VLP-16 scan inherits their drift (docs/METHOD.md, Mapping).
  int local_map_lag_keyframes = 0;
  // Keyframes older than the newest keyframe_merge_after are merged keyframe_merge_group at a
  // time: their clouds join one of them, voxel-filtered (a place seen from ten keyframes is stored
  // once), and a group where an older merged keyframe already lies is not stored again. Memory
  // then grows with the ground covered, not with the time driven. 1 turns merging off.
  int keyframe_merge_group = 10;
  int keyframe_merge_after = 100;
  // m: a merged keyframe keeps the points within this distance of it (points farther away are
  // sparse, and other keyframes see them closer); 0 keeps all.
  double keyframe_merge_radius = 20.0;
  double degeneracy_eigenvalue = 100;  // LOAM's threshold on the normal equations' eigenvalues
  // The 1-sigma error of a scan-to-map residual (m): the information the match publishes, and
  // how the motion sensors' priors weigh against the LiDAR's correspondences. Larger than the
  // range noise: neighbouring correspondences share their map points and their errors.
  double residual_sigma = 0.05;
  // A direction of the motion the correspondences fix no better than this (1 sigma, the other
  // block marginalised) is degenerate: the motion sensors' prior holds it.
  double degenerate_translation_sigma = 0.1;   // m
  double degenerate_rotation_sigma_deg = 1.0;  // deg
  // Gravity, from an IMU on a moving vehicle, is trusted no better than this (deg): until it
  // turns, an accelerometer's bias cannot be told from a tilt.
  double gravity_sigma_deg = 0.5;
  // Weight of a prior pulling the translation along the ambient filter's weak direction toward
  // the odometry's prediction, times mu; 0 turns it off.
  double weak_direction_prior = 0.0;
  // The vertical-structure prior (core/mapping/vertical_structure.h): the weight of each wall
  // patch's residual, its normal's vertical component in the map frame; 0 turns it off.
  double vertical_prior_weight = 0.0;
  double vertical_prior_max_tilt_deg = 5.0;  // patches this near a vertical wall count as walls
  // The guess for scan-to-map: the odometry's motion, unless it differs from the previous scan's
  // mapped motion by more than this (m per scan) or max_motion_change_deg; then that motion
  // (constant velocity). 0 = off. A vehicle cannot change its speed by 0.3 m per scan at 10 Hz.
  // A file gives these and max_gated_scans for 0.1 s scans (kReferenceScanPeriod).
  double max_motion_change = 0.0;
  double max_motion_change_deg = 0.0;
  // After this many scans in a row gated, the odometry's motion is taken again: a velocity that
  // scan-to-map could not correct must not hold every later scan. 0 = the gate never lets go.
  int max_gated_scans = 0;
};

// An optional IMU (core/motion_sensors/): used only when a run is given its samples. Noise
// densities and bias random walks are continuous-time values; the defaults are an Analog
// Devices ADIS16448's (docs/SENSORS.md).
struct ImuParams {
  // The IMU's pose in the LiDAR frame (the transform lidar -> imu): roll, pitch, yaw (deg, applied
  // as R = Rz(yaw) Ry(pitch) Rx(roll)) and translation (m). A node takes it from TF when a static
  // transform exists.
  std::vector<double> extrinsic_rpy_deg{0.0, 0.0, 0.0};
  std::vector<double> extrinsic_xyz_m{0.0, 0.0, 0.0};
  double time_offset_s = 0.0;          // added to the IMU's stamps to put them on the LiDAR's clock
  double gyro_noise_density = 1.7e-4;  // rad/s/sqrt(Hz)
  double accel_noise_density = 2.0e-3;     // m/s^2/sqrt(Hz)
  double gyro_bias_random_walk = 2.0e-5;   // rad/s^2/sqrt(Hz)
  double accel_bias_random_walk = 3.0e-3;  // m/s^3/sqrt(Hz)
  // 1-sigma of the biases at start-up (before the filter has seen any motion).
  double gyro_bias_sigma = 8.7e-3;  // rad/s
  double accel_bias_sigma = 0.196;  // m/s^2
  double gravity = 9.81;            // m/s^2
  // Samples further apart than this leave a gap: the scans it touches fall back to LiDAR-only.
  double max_gap_s = 0.05;
  // Samples beyond these are not a vehicle's motion but a fault: dropped and counted.
  double max_angular_velocity = 35.0;  // rad/s (2000 deg/s, a MEMS gyro's largest range)
  double max_acceleration = 160.0;     // m/s^2 (16 g)
};

// An optional wheel odometry (core/motion_sensors/): the twist of the vehicle's base frame.
struct WheelOdometryParams {
  // The base frame's pose in the LiDAR frame (the transform lidar -> base), as ImuParams. A node
  // takes it from TF when a static transform exists.
  std::vector<double> extrinsic_rpy_deg{0.0, 0.0, 0.0};
  std::vector<double> extrinsic_xyz_m{0.0, 0.0, 0.0};
  double time_offset_s = 0.0;
  // 1-sigma errors when a message reports no variance.
  double speed_sigma = 0.05;         // m/s
  double yaw_rate_sigma_deg = 1.15;  // deg/s
  double max_gap_s = 0.2;            // s
  double max_speed = 70.0;           // m/s: faster is a fault, dropped and counted
  double max_yaw_rate_deg = 360.0;   // deg/s
};

// Robust loss on a pose-graph edge's whitened residual norm |r| (in sigmas). kHuber: quadratic up
// to |r| = scale, linear beyond. kCauchy: scale^2 * log(1 + |r|^2 / scale^2), whose pull on the
// poses fades once |r| is well beyond scale.
enum class RobustLoss { kNone, kHuber, kCauchy };

// Loop candidates from the place descriptor (core/loop_closure/place_descriptor.h), whatever the
// drift: the keyframes whose ring keys are nearest are compared in full.
struct PlaceRecognitionParams {
  bool enabled = true;
  int rings = 20;
  int sectors = 60;
  double max_radius = 80.0;    // m
  double height_offset = 2.0;  // m added to heights: about the sensor's height above the ground
  int candidates = 10;         // nearest ring keys compared in full
  double max_distance = 0.3;   // descriptor distance in [0, 1] up to which a place is the same
  // Distinctness: the best match must be closer than max_ratio times the best match elsewhere
  // (more than elsewhere_distance from it); a street of identical houses matches every house
  // alike, and none is taken.
  double max_ratio = 0.7;
  double elsewhere_distance = 20.0;  // m
};

// Loop closure: candidates from place recognition, else LeGO-LOAM's radius search around the
// (drifted) position; ICP of the newest keyframe against the candidate's neighbourhood, accepted
// on inliers; a loop enters the pose graph once a second loop agrees with it.
struct LoopClosureParams {
  bool enabled = true;
  PlaceRecognitionParams place;
  double search_radius = 7.0;        // m: radius-search candidates lie this close ...
  double min_time_gap = 30.0;        // s: and every candidate is at least this much older
  double min_loop_path = 40.0;       // m: ... and this far back along the path driven
  int neighbourhood_keyframes = 25;  // the candidate's map: it and this many on either side
  // Verification: the current keyframe's points within verify_radius (the candidate's map holds
  // merged keyframes' points that near, MappingParams::keyframe_merge_radius) after ICP; accepted
  // when at least min_inlier_ratio of them lie within inlier_distance of the map and those
  // inliers' mean squared distance is at most max_inlier_mse.
  double verify_radius = 20.0;     // m
  double inlier_distance = 1.0;    // m
  double min_inlier_ratio = 0.95;  // of the points
  double max_inlier_mse = 0.1;     // m^2
  // Consistency: a verified loop waits for a second, verified within consistency_window keyframes,
  // whose relative pose agrees with it through both sides' odometry; only the pair enters the
  // pose graph. After each optimisation a loop whose edge is still more than max_loop_residual
  // sigmas off is removed and the graph solved again.
  int consistency_window = 30;           // keyframes
  double consistency_translation = 0.5;  // m
  double consistency_rotation_deg = 2.0;
  // Drift bound: a verified loop may move its keyframe from where the odometry put it by at most
  // max_drift_fraction of the path driven between its two ends, plus max_drift_offset. A larger
  // correction is a place that only looks the same (a street of identical houses), not drift.
  double max_drift_fraction = 0.05;
  double max_drift_offset = 5.0;    // m
  double max_loop_residual = 10.0;  // sigmas
  // s: after loops entered the pose graph, the next attempt waits this long (a place driven
  // again is closed once, not at every keyframe).
  double min_closure_interval = 10.0;
  double voxel_size = 0.4;                         // m: leaf of the candidate's map; 0 = no filter
  double icp_max_correspondence_distance = 100.0;  // m
  int icp_max_iterations = 30;
  // ICP aligns every n-th point of the newest keyframe, at most this many: bounds its time.
  int icp_max_points = 2000;
  // A verified loop's pose refined as mapping places a scan: the keyframe's edges and surfaces
  // (every n-th, at most icp_max_points) matched to lines and planes of the candidate's map.
  // Point-to-point ICP stops centimetres to decimetres off where the keyframe sees what the map
  // does not, and where it matches sparse rings point to point.
  bool refine = true;
  // A loop closure is spread over the scans from its keyframe on, so that no scan pays for all of
  // it; each scan does the next of these pieces (or the voxel filter, or the KD-tree). The
  // detection does not depend on their size.
  int map_points_per_scan = 20000;    // keyframe points placed into the candidate's map
  int icp_iterations_per_scan = 2;    // ICP iterations (the final fitness counts as one), then
                                      // the refinement's match iterations
  int graph_iterations_per_scan = 1;  // pose-graph solver iterations, once the loop is accepted
  // A solver iteration's cost grows with the nodes: past this many keyframes the loop is
  // optimised over a subset of them (see reduce_graph), so that a long run's iteration stays
  // bounded.
  int graph_max_nodes = 200;
  // Pose-graph weights (1-sigma errors): of the odometry between consecutive keyframes and of a
  // loop measured by ICP.
  double odometry_sigma_translation = 0.05;  // m
  double odometry_sigma_rotation_deg = 0.5;
  double loop_sigma_translation = 0.2;  // m
  double loop_sigma_rotation_deg = 1.0;
  // On loop edges. With the Cauchy loss a loop that disagrees with the odometry by more than about
  // 2 * robust_loss_scale accumulated odometry sigmas (Mahalanobis) is mostly ignored; below
  // that it closes fully.
  RobustLoss robust_loss = RobustLoss::kCauchy;
  double robust_loss_scale = 2.0;  // sigmas
};

// Localization on a saved map (run_sequence --localize, launch/localization.launch): every scan
// matched against the map's keyframes near it and the newest keyframes of this drive; none joins
// the map.
struct LocalizationParams {
  // Tracking holds while at least this share of the scan's features find a line or plane in the
  // map; lost_after_scans scans in a row below it and the localization is lost (a file gives it
  // for 0.1 s scans: kReferenceScanPeriod).
  double min_match_ratio = 0.3;
  int lost_after_scans = 5;
  // While lost (or at the start) the scan is aligned by ICP from the predicted pose to the map's
  // keyframes near it (the nearest within search_radius and its neighbours, as a loop candidate's
  // map) and accepted on loop closure's inlier test; at most once a retry_period.
  double search_radius = 20.0;  // m
  double retry_period = 1.0;    // s
  // This drive's newest keyframes that join the map's for matching (and leave it again).
  int recent_keyframes = 10;
};

// The map a run saves (run_sequence --save-map, map_optimization's save_map service).
struct SavedMapParams {
  static constexpr double kMinVoxel = 0.01, kMaxVoxel = 10.0;  // m: the leaves a save may use
  double voxel_size = 0.2;                                     // m: leaf of the saved global map
};

// Settings of the clustering benchmark tool (segmentation_bench), the same for every method.
struct ClusteringBenchmarkParams {
  // Clusters with fewer points are not output. 1 counts every cluster: the benchmark's score
  // (best IoU per labelled box) can only fall when clusters are left out.
  int min_cluster_points = 1;
};

struct Config {
  std::string source;  // file the config came from, for messages
  SensorParams sensor;
  SegmentationParams segmentation;
  AmbientFilterParams ambient;
  FeatureParams features;
  OdometryParams odometry;
  MappingParams mapping;
  LoopClosureParams loop_closure;
  LocalizationParams localization;
  SavedMapParams saved_map;
  ClusteringBenchmarkParams clustering_benchmark;
  ImuParams imu;
  WheelOdometryParams wheel_odometry;
};

// Loads and checks a config file. Throws ConfigError naming the file, the key and the allowed
// range on the first bad value; unknown keys are errors too (a typo must not pass silently).
Config load_config(const std::string& path);
// Several files, each later one's keys replacing the earlier ones' (a sensor's config, then a
// robot's extrinsics): section by section, key by key.
Config load_config(const std::vector<std::string>& paths);
// The same from YAML text; `source` names it in messages.
Config parse_config(const std::string& yaml_text, const std::string& source);

// Cross-field checks shared by the loader and code that builds params by hand.
void validate(const SensorParams& sensor, const std::string& source);

}  // namespace adaptive_lego_loam
