#include "adaptive_lego_loam/core/mapping/vertical_structure.h"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <vector>

#include "adaptive_lego_loam/core/spatial/voxel_hash.h"

namespace adaptive_lego_loam {
namespace {

constexpr double kInversePatchSize = 1.0;  // 1 / m: a patch is the points of a 1 m cube
constexpr int kMinPoints = 8;
// A patch is flat when its thinnest spread is this small against the next (variance ratio), and
// spread in two directions when the next is at least this (m^2): not a line of one ring.
constexpr double kFlatness = 0.02;
constexpr double kMinSpread = 0.01;
// Fewer wall patches than this in a scan give no prior: a lone barrier must not steer the map.
constexpr std::size_t kMinPatches = 20;

// A patch's point count, sum and sum of outer products (its upper triangle: xx xy xz yy yz zz).
struct Moments {
  int count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::array<double, 6> outer{};

  void add(const Eigen::Vector3d& x) {
    ++count;
    sum += x;
    outer[0] += x.x() * x.x();
    outer[1] += x.x() * x.y();
    outer[2] += x.x() * x.z();
    outer[3] += x.y() * x.y();
    outer[4] += x.y() * x.z();
    outer[5] += x.z() * x.z();
  }

  Eigen::Matrix3d covariance(const Eigen::Vector3d& mean) const {
    Eigen::Matrix3d second;
    second << outer[0], outer[1], outer[2], outer[1], outer[3], outer[4], outer[2], outer[4],
        outer[5];
    return second / count - mean * mean.transpose();
  }
};

}  // namespace

std::vector<Eigen::Vector3d> wall_normals(const Cloud& points, const Eigen::Matrix3d& rotation,
                                          double max_tilt_deg) {
  // The table holds indices into a dense array: small slots keep the scattered writes in cache.
  VoxelHashTable<uint32_t> patch_index;
  std::vector<Moments> patches;
  patch_index.reserve(points.size() / 8);
  patches.reserve(points.size() / 8);
  // A patch whose whole cube lies below the sensor (in the map frame) has its mean there too and
  // is no wall: its points (the ground, most of them) need no moments. The cube's highest point
  // is its corner of smallest coordinates raised by the up axis' positive components.
  const Eigen::RowVector3d up = rotation.row(2);
  const double cube_rise = up.cwiseMax(0.0).sum() / kInversePatchSize;
  constexpr double kBelow = -1e-6;  // m: clear of the rounding of the mean's height
  for (const CloudPoint& p : points) {
    const int64_t x = voxel_index(p.x, kInversePatchSize), y = voxel_index(p.y, kInversePatchSize),
                  z = voxel_index(p.z, kInversePatchSize);
    const Eigen::Vector3d corner(static_cast<double>(x), static_cast<double>(y),
                                 static_cast<double>(z));
    if (up.dot(corner) / kInversePatchSize + cube_rise < kBelow) continue;
    bool inserted = false;
    uint32_t& index = patch_index.find_or_insert(pack_voxel_key(x, y, z), &inserted);
    if (inserted) {
      index = static_cast<uint32_t>(patches.size());
      patches.emplace_back();
    }
    patches[index].add(p.getVector3fMap().cast<double>());
  }
  const double max_vertical = std::sin(max_tilt_deg * M_PI / 180.0);
  std::vector<Eigen::Vector3d> normals;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  for (const Moments& patch : patches) {
    if (patch.count < kMinPoints) continue;
    const Eigen::Vector3d mean = patch.sum / patch.count;
    // Walls rise above the sensor; near the ground, barriers, curbs and embankments lean.
    if ((rotation * mean).z() <= 0.0) continue;
    solver.computeDirect(patch.covariance(mean));
    const Eigen::Vector3d spread = solver.eigenvalues();
    if (spread(1) < kMinSpread || spread(0) > kFlatness * spread(1)) continue;
    const Eigen::Vector3d normal = solver.eigenvectors().col(0);
    if (std::fabs((rotation * normal).z()) > max_vertical) continue;
    normals.push_back(normal);
  }
  if (normals.size() < kMinPatches) normals.clear();
  return normals;
}

}  // namespace adaptive_lego_loam
