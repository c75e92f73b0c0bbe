#include "adaptive_lego_loam/sim/simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {
namespace {

constexpr uint64_t kNoiseStream = 0x4E4F495345ull;  // "NOISE"

}  // namespace

LidarSimulator::LidarSimulator(const LidarModel& model, std::shared_ptr<const World> world,
                               std::shared_ptr<const Trajectory> trajectory, uint64_t seed)
    : model_(model),
      trajectory_(std::move(trajectory)),
      // Beams start up to a few decimetres above the sensor origin; moving objects a few metres.
      caster_(std::move(world), static_cast<float>(model.sensor().max_range) + 1.0f),
      seed_(seed) {}

void LidarSimulator::make_column_poses(double sweep_start, const Eigen::Isometry3d& start_pose) {
  const int columns = model_.columns();
  column_poses_.resize(columns);
  for (int column = 0; column < columns; ++column) {
    column_poses_[column] = model_.options().motion_distortion
                                ? trajectory_->sensor_pose(sweep_start + model_.column_time(column))
                                : start_pose;
  }
}

void LidarSimulator::make_rays(int first_column, int width) {
  const int beams = model_.beams(), footprint = footprint_rays();
  rays_.resize(static_cast<std::size_t>(beams) * footprint * width);
  const float max_distance = static_cast<float>(model_.sensor().max_range) + 1.0f;
  const double half_angle = 0.5e-3 * model_.options().beam_divergence_mrad;
  Ray* ray = rays_.data();
  for (int beam = 0; beam < beams; ++beam) {
    for (int k = 0; k < footprint; ++k) {
      for (int column = first_column; column < first_column + width; ++column, ++ray) {
        const Eigen::Isometry3d& pose = column_poses_[column];
        Eigen::Vector3d direction = model_.direction(beam, column);
        if (k > 0) {
          // The footprint's rim: left, right, above, below the centre, half the divergence off.
          const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(direction).normalized();
          const Eigen::Vector3d up = direction.cross(across);
          const Eigen::Vector3d offsets[4] = {across, -across, up, -up};
          direction = (direction + std::tan(half_angle) * offsets[k - 1]).normalized();
        }
        ray->origin = (pose * model_.beam_origin(beam)).cast<float>();
        ray->direction = (pose.linear() * direction).cast<float>();
        ray->max_distance = max_distance;
      }
    }
  }
}

std::optional<LidarSimulator::Echo> LidarSimulator::strongest_echo(const Hit* hits, int count,
                                                                   std::size_t stride) const {
  struct Return {
    float range, energy;
    int ray;
  };
  Return echoes[5];
  int found = 0;
  for (int k = 0; k < count; ++k) {
    const Hit& hit = hits[k * stride];
    if (!hit.valid() || hit.distance < model_.sensor().min_range ||
        hit.distance > model_.sensor().max_range)
      continue;
    // Received power of a surface filling its share of the footprint: reflectivity over r^2.
    const float energy = std::max(hit.reflectivity, 0.01f) / (hit.distance * hit.distance);
    echoes[found++] = {hit.distance, energy, k};
  }
  if (found == 0) return std::nullopt;
  if (count == 1) return Echo{hits[0], 0};
  std::sort(echoes, echoes + found,
            [](const Return& a, const Return& b) { return a.range < b.range; });
  const float merge = static_cast<float>(model_.options().echo_merge_distance_m);
  Echo best;
  float best_energy = -1.0f;
  for (int first = 0; first < found;) {
    // Echoes within the merge distance of the group's nearest make one: a mixed pixel.
    int last = first;
    float energy = 0.0f, weighted_range = 0.0f;
    int strongest = echoes[first].ray;
    float strongest_energy = -1.0f;
    while (last < found && echoes[last].range - echoes[first].range <= merge) {
      energy += echoes[last].energy;
      weighted_range += echoes[last].energy * echoes[last].range;
      if (echoes[last].energy > strongest_energy) {
        strongest_energy = echoes[last].energy;
        strongest = echoes[last].ray;
      }
      ++last;
    }
    if (energy > best_energy) {
      best_energy = energy;
      best = {hits[strongest * stride], strongest};
      best.hit.distance = weighted_range / energy;
    }
    first = last;
  }
  return best;
}

SimFrame LidarSimulator::render(int frame) {
  SimFrame out;
  render(frame, out);
  return out;
}

void LidarSimulator::render(int frame, SimFrame& out) {
  out.time = trajectory_->frame_time(frame);
  out.sensor_pose = trajectory_->sensor_pose(out.time);
  const double period = model_.sensor().scan_period;
  // A moving sweep ends at the frame's time, as a Velodyne driver stamps a scan with its last
  // packet: the frame's pose is the sweep's end, where de-skewing puts the scan. Without motion
  // every ray leaves from the frame's pose.
  const double sweep_start = model_.options().motion_distortion ? out.time - period : out.time;
  const Eigen::Vector3d middle = trajectory_->sensor_pose(sweep_start + 0.5 * period).translation();

  auto started = std::chrono::steady_clock::now();
  // Moving objects stand where they are at the sweep's middle for the whole sweep.
  caster_.prepare(frame, sweep_start + 0.5 * period, middle);
  make_column_poses(sweep_start, out.sensor_pose);
  ray_casting_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  out.scan.stamp = out.time;
  out.scan.has_ring = out.scan.has_time = true;
  out.scan.points.clear();
  out.labels.clear();
  out.normals.clear();
  out.exact_points.clear();
  out.exact_normals.clear();
  const Eigen::Isometry3d world_to_scan = out.sensor_pose.inverse();
  const Eigen::Matrix3f world_to_scan_rotation = world_to_scan.linear().cast<float>();
  Rng rng(derive_seed(seed_, kNoiseStream, static_cast<uint64_t>(frame)));
  const int beams = model_.beams(), columns = model_.columns();
  // A block of columns at a time, so that its rays and hits stay in cache between casting and
  // reading them. Rays and hits are stored beam by beam (neighbours in a packet share a beam);
  // points come out column by column, the order a Velodyne reports them in.
  constexpr int kBlock = 16;
  for (int block = 0; block < columns; block += kBlock) {
    const int width = std::min(kBlock, columns - block);
    started = std::chrono::steady_clock::now();
    make_rays(block, width);
    hits_.resize(rays_.size());
    caster_.cast(rays_.data(), rays_.size(), hits_.data());
    ray_casting_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const int footprint = footprint_rays();
    for (int c = 0; c < width; ++c) {
      const int column = block + c;
      const Eigen::Matrix3f to_sensor = column_poses_[column].linear().transpose().cast<float>();
      const float time = static_cast<float>(model_.column_time(column));
      for (int beam = 0; beam < beams; ++beam) {
        // The beam's centre ray; its footprint rays follow `width` apart.
        const std::size_t index = static_cast<std::size_t>(beam) * footprint * width + c;
        const std::optional<Echo> echo = strongest_echo(&hits_[index], footprint, width);
        if (!echo || !add_return(echo->hit, rays_[index].direction, beam, column, rng, out))
          continue;
        out.scan.points.back().time = time;
        out.normals.push_back(to_sensor * echo->hit.normal);
        const std::size_t surface = index + static_cast<std::size_t>(echo->footprint_ray) * width;
        const Ray& ray = rays_[surface];
        const Eigen::Vector3f hit = ray.origin + hits_[surface].distance * ray.direction;
        out.exact_points.push_back((world_to_scan * hit.cast<double>()).cast<float>());
        out.exact_normals.push_back(world_to_scan_rotation * hits_[surface].normal);
      }
    }
  }
}

bool LidarSimulator::add_return(const Hit& hit, const Eigen::Vector3f& direction, int beam,
                                int column, Rng& rng, SimFrame& out) const {
  if (!hit.valid() || hit.distance < model_.sensor().min_range ||
      hit.distance > model_.sensor().max_range)
    return false;
  const double cos_incidence = -hit.normal.dot(direction);
  const double probability = model_.return_probability(cos_incidence);
  if (probability < 1.0 && rng.uniform() >= probability) return false;
  const double noise = model_.options().range_noise_m;
  const double range = hit.distance + (noise > 0.0 ? rng.normal(0.0, noise) : 0.0);
  const Eigen::Vector3d local = model_.beam_origin(beam) + range * model_.direction(beam, column);
  ScanPoint point;
  point.x = static_cast<float>(local.x());
  point.y = static_cast<float>(local.y());
  point.z = static_cast<float>(local.z());
  // In [0, 1] as KITTI's reflectance: Lambertian, from the surface's reflectivity.
  point.intensity = static_cast<float>(hit.reflectivity * cos_incidence);
  point.ring = model_.ring(beam);
  out.scan.points.push_back(point);
  out.labels.push_back(hit.label);
  return true;
}

}  // namespace adaptive_lego_loam::sim
