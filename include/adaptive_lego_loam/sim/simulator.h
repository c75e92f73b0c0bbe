#pragma once
// One simulated sweep: a ray per beam and column from where the sensor is when the column fires,
// with range noise, dropouts, intensity, ring, time and the label of the surface hit.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/sim/lidar_model.h"
#include "adaptive_lego_loam/sim/random.h"
#include "adaptive_lego_loam/sim/ray_caster.h"
#include "adaptive_lego_loam/sim/trajectory.h"
#include "adaptive_lego_loam/sim/world.h"

namespace adaptive_lego_loam::sim {

struct SimFrame {
  Scan scan;  // sensor frame, with ring (LidarModel::ring) and time (s from the sweep's start)
  std::vector<uint32_t> labels;          // per point, SemanticKITTI packing
  std::vector<Eigen::Vector3f> normals;  // per point, sensor frame, unit, facing the sensor
  // Per point, the surface it came from without range noise (of a mixed echo, its strongest
  // surface's hit) and that surface's normal, both in the sensor frame at the scan's time
  // (`sensor_pose`): the scan's exact geometry, from which its true observability follows.
  std::vector<Eigen::Vector3f> exact_points, exact_normals;
  // World, at the scan's time: where a skewed sweep ends (its first firing a scan period before).
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();
  double time = 0.0;
};

class LidarSimulator {
 public:
  LidarSimulator(const LidarModel& model, std::shared_ptr<const World> world,
                 std::shared_ptr<const Trajectory> trajectory, uint64_t seed);

  // Frames may be rendered in any order; frame f's noise depends only on the seed and f.
  SimFrame render(int frame);
  // The same into `out`, reusing its buffers.
  void render(int frame, SimFrame& out);

  const LidarModel& model() const { return model_; }
  double ray_casting_seconds() const { return ray_casting_seconds_; }

 private:
  void make_column_poses(double sweep_start, const Eigen::Isometry3d& start_pose);
  // Rays of columns [first_column, first_column + width), beam by beam and per beam footprint ray
  // by footprint ray (centre first), into rays_.
  void make_rays(int first_column, int width);
  // The echo a beam reports from its footprint rays' hits (`count` of them, `stride` apart,
  // the centre first): the strongest after merging echoes closer than the merge distance, at its
  // energy-weighted range, and which footprint ray hit its strongest surface. Nothing when no
  // hit lies within the sensor's range.
  struct Echo {
    Hit hit;
    int footprint_ray = 0;
  };
  std::optional<Echo> strongest_echo(const Hit* hits, int count, std::size_t stride) const;
  // Appends the point (without its time) and label of a hit that comes back; false when the
  // return is lost (out of range, grazing incidence).
  bool add_return(const Hit& hit, const Eigen::Vector3f& direction, int beam, int column, Rng& rng,
                  SimFrame& out) const;
  int footprint_rays() const { return model_.options().beam_divergence_mrad > 0.0 ? 5 : 1; }

  LidarModel model_;
  std::shared_ptr<const Trajectory> trajectory_;
  RayCaster caster_;
  uint64_t seed_;
  std::vector<Ray> rays_;  // of a block of columns, beam-major: neighbours in a packet share a beam
  std::vector<Hit> hits_;
  std::vector<Eigen::Isometry3d> column_poses_;
  double ray_casting_seconds_ = 0.0;
};

}  // namespace adaptive_lego_loam::sim
