#pragma once
// Keyframes along a square path through a scene of boxes, for the loop-closure tests.

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"
#include "support/poses.h"

namespace adaptive_lego_loam::test {

constexpr double kRange = 20.0;  // m: what a keyframe sees

// A flat patch origin + s * u + t * v, s and t in [0, 1], sampled at `density` points per m^2.
struct Patch {
  Eigen::Vector3d origin, u, v;
  double density;
};

// Ground 1.5 m below the sensor and a dozen boxes of random size, place and heading around the
// 10 m square the keyframes drive.
inline std::vector<Patch> scene(unsigned seed) {
  std::mt19937 random(seed);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
  };
  const double ground_z = -1.5;
  std::vector<Patch> patches{{{-20, -20, ground_z}, {50, 0, 0}, {0, 50, 0}, 0.5}};
  for (int box = 0; box < 12; ++box) {
    const Eigen::Vector3d centre(uniform(-12, 22), uniform(-12, 22), ground_z);
    const Eigen::Matrix3d heading =
        Eigen::AngleAxisd(uniform(0, M_PI), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d x = heading * Eigen::Vector3d(uniform(1, 4), 0, 0);
    const Eigen::Vector3d y = heading * Eigen::Vector3d(0, uniform(1, 4), 0);
    const Eigen::Vector3d z(0, 0, uniform(1, 5));
    const Eigen::Vector3d corner = centre - x / 2 - y / 2;
    patches.push_back({corner, x, z, 4.0});
    patches.push_back({corner, y, z, 4.0});
    patches.push_back({corner + x, y, z, 4.0});
    patches.push_back({corner + y, x, z, 4.0});
    patches.push_back({corner + z, x, y, 4.0});
  }
  return patches;
}

// Points on the patches within kRange of `true_pose`, in its sensor frame. Each keyframe draws
// its own samples, so no two clouds share a point.
inline CloudPtr observe(const std::vector<Patch>& patches, const Eigen::Isometry3d& true_pose,
                        unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Isometry3d to_sensor = true_pose.inverse();
  CloudPtr cloud(new Cloud);
  for (const Patch& patch : patches) {
    const int samples = static_cast<int>(patch.u.cross(patch.v).norm() * patch.density);
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector3d point = patch.origin + unit(random) * patch.u + unit(random) * patch.v;
      if ((point - true_pose.translation()).norm() > kRange) continue;
      CloudPoint p;
      p.getVector3fMap() = (to_sensor * point).cast<float>();
      p.intensity = 0.0f;
      cloud->push_back(p);
    }
  }
  return cloud;
}

// The 40 poses of a counter-clockwise 10 m square, 1 m apart, starting at the origin heading +x
// and ending at (0, 1) heading -y.
inline Poses square_path() {
  Poses poses;
  const double corners[4][2] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const double directions[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  for (int k = 0; k < 40; ++k) {
    const int side = k / 10;
    const double along = k % 10;
    poses.push_back(planar(corners[side][0] + along * directions[side][0],
                           corners[side][1] + along * directions[side][1], 90.0 * side));
  }
  return poses;
}

// One keyframe per pose, 1 s apart; the clouds are seen from `truth`, the poses are `estimates`.
inline std::vector<Keyframe> keyframes_along(const Poses& truth, const Poses& estimates,
                                             unsigned scene_seed = 7) {
  const std::vector<Patch> patches = scene(scene_seed);
  std::vector<Keyframe> keyframes;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    Keyframe keyframe;
    keyframe.index = keyframe.frame = static_cast<int>(k);
    keyframe.stamp = static_cast<double>(k);
    keyframe.pose = estimates[k];
    // Split the samples over both clouds so that both are used.
    const CloudPtr all = observe(patches, truth[k], 1000 + static_cast<unsigned>(k));
    Cloud corners, surfaces;
    for (std::size_t i = 0; i < all->size(); ++i)
      (i % 5 == 0 ? corners : surfaces).push_back((*all)[i]);
    keyframe.corners = pack(corners);
    keyframe.surfaces = pack(surfaces);
    keyframes.push_back(keyframe);
  }
  return keyframes;
}

// The last keyframe's pose is off by 1 m and 3 deg (the error a loop closure has to find).
inline const Eigen::Isometry3d kOffset = planar(-0.8, -0.6, 3.0);

struct OffsetCase {
  Poses truth = square_path();
  Poses estimates = [this] {
    Poses poses = truth;
    poses.back() = kOffset * poses.back();
    return poses;
  }();
  std::vector<Keyframe> keyframes = keyframes_along(truth, estimates);
};

inline double rotation_deg(const Eigen::Isometry3d& pose) {
  return Eigen::AngleAxisd(pose.rotation()).angle() / kDeg;
}

}  // namespace adaptive_lego_loam::test
