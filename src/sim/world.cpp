#include "adaptive_lego_loam/sim/world.h"

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/sim/objects.h"

namespace adaptive_lego_loam::sim {

uint32_t World::add_surface(SemanticClass semantic, uint16_t instance, float reflectivity) {
  surfaces.push_back({semantic, instance, reflectivity});
  return static_cast<uint32_t>(surfaces.size() - 1);
}

uint16_t World::new_instance() {
  if (next_instance_ > 0xFFFF) {
    throw std::runtime_error(
        "scene has more than 65535 objects, the most SemanticKITTI's 16-bit instance ids hold; "
        "simulate fewer frames");
  }
  return static_cast<uint16_t>(next_instance_++);
}

TileKey World::tile_of(const Eigen::Vector3f& point) const {
  return {static_cast<int>(std::floor(point.x() / tile_size)),
          static_cast<int>(std::floor(point.y() / tile_size))};
}

Eigen::Isometry3d path_motion_pose(const Path& path, const PathMotion& motion, double time) {
  const Path::Frame frame = path.at(motion.start_s + motion.speed * time);
  const double heading = motion.speed < 0.0 ? frame.heading + M_PI : frame.heading;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(frame.position + motion.lateral * frame.left);
  pose.rotate(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()));
  const double pitch = std::atan(motion.speed < 0.0 ? -frame.grade : frame.grade);
  pose.rotate(Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()));
  return pose;
}

int walker_pose(const Walker& walker, double time) {
  // About one stride per second at walking speed.
  const double stride_hz = 0.6 * std::abs(walker.motion.speed);
  const double cycles = (2.0 * M_PI * stride_hz * time + walker.gait_phase) / (2.0 * M_PI);
  const int pose = static_cast<int>(std::lround((cycles - std::floor(cycles)) * kWalkerPoses));
  return pose % kWalkerPoses;
}

GeometrySet walker_pose_geometry(int pose, uint32_t surface) {
  const float swing = static_cast<float>(std::sin(2.0 * M_PI * pose / kWalkerPoses));
  GeometrySet set;
  add_person(set, Eigen::Isometry3f::Identity(), kWalkerHeight, swing, surface);
  return set;
}

}  // namespace adaptive_lego_loam::sim
