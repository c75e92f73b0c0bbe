#include "adaptive_lego_loam/core/mapping/vertical_structure.h"

#include <Eigen/Eigenvalues>
#include <cmath>

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

struct Moments {
  int count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
};

}  // namespace

std::vector<Eigen::Vector3d> wall_normals(const Cloud& points, const Eigen::Matrix3d& rotation,
                                          double max_tilt_deg) {
  VoxelHashTable<Moments> patches;
  patches.reserve(points.size() / 4);
  for (const CloudPoint& p : points) {
    Moments& patch = patches.find_or_insert(voxel_key(p, kInversePatchSize));
    const Eigen::Vector3d x = p.getVector3fMap().cast<double>();
    ++patch.count;
    patch.sum += x;
    patch.outer += x * x.transpose();
  }
  const double max_vertical = std::sin(max_tilt_deg * M_PI / 180.0);
  std::vector<Eigen::Vector3d> normals;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  patches.for_each([&](uint64_t, const Moments& patch) {
    if (patch.count < kMinPoints) return;
    const Eigen::Vector3d mean = patch.sum / patch.count;
    solver.computeDirect(patch.outer / patch.count - mean * mean.transpose());
    const Eigen::Vector3d spread = solver.eigenvalues();
    if (spread(1) < kMinSpread || spread(0) > kFlatness * spread(1)) return;
    // Walls rise above the sensor; near the ground, barriers, curbs and embankments lean.
    if ((rotation * mean).z() <= 0.0) return;
    const Eigen::Vector3d normal = solver.eigenvectors().col(0);
    if (std::fabs((rotation * normal).z()) > max_vertical) return;
    normals.push_back(normal);
  });
  if (normals.size() < kMinPatches) normals.clear();
  return normals;
}

}  // namespace adaptive_lego_loam
