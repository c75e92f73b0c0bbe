#include "placement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adaptive_lego_loam::sim {

bool Placer::claim(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half,
                   double road_clearance, const Path* road, int owner) {
  if (road_clearance > 0.0) {
    const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
    const int nx = static_cast<int>(std::ceil(2.0 * half.x())) + 1;
    const int ny = static_cast<int>(std::ceil(2.0 * half.y())) + 1;
    Path::Nearest unused;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        const Eigen::Vector2d p = centre + (-half.x() + 2.0 * half.x() * i / (nx - 1)) * ex +
                                  (-half.y() + 2.0 * half.y() * j / (ny - 1)) * ey;
        if ((road ? *road : path_).nearest(p, road_clearance, unused)) return false;
      }
    }
  }
  const std::vector<int64_t> cells = cells_of(centre, yaw, half);
  for (int64_t key : cells) {
    if (taken_.count(key)) return false;
    const auto reserved = reserved_.find(key);
    if (reserved != reserved_.end() && reserved->second != owner) return false;
  }
  taken_.insert(cells.begin(), cells.end());
  return true;
}

std::vector<int64_t> Placer::cells_of(const Eigen::Vector2d& centre, double yaw,
                                      const Eigen::Vector2d& half) const {
  const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
  std::vector<int64_t> cells;
  const double reach = half.norm();
  for (double x = std::floor((centre.x() - reach) / kCell); x * kCell <= centre.x() + reach; ++x) {
    for (double y = std::floor((centre.y() - reach) / kCell); y * kCell <= centre.y() + reach;
         ++y) {
      const Eigen::Vector2d offset = Eigen::Vector2d((x + 0.5) * kCell, (y + 0.5) * kCell) - centre;
      if (std::abs(offset.dot(ex)) > half.x() + 0.5 * kCell ||
          std::abs(offset.dot(ey)) > half.y() + 0.5 * kCell)
        continue;
      // Shifted as unsigned: a negative index's shift is undefined.
      cells.push_back(
          static_cast<int64_t>((static_cast<uint64_t>(static_cast<int64_t>(x)) << 32) ^
                               (static_cast<uint64_t>(static_cast<int64_t>(y)) & 0xFFFFFFFFull)));
    }
  }
  return cells;
}

double Layout::ground(const Eigen::Vector2d& xy) const {
  Path::Nearest nearest;
  if (path.nearest(xy, p.road_half_width + p.sidewalk_width, nearest)) {
    if (std::abs(nearest.lateral) <= p.road_half_width) return nearest.height;
    if (p.sidewalk_width > 0.0) return nearest.height + p.curb_height;
  }
  return terrain.height(xy);
}

void Layout::add_plant(const std::vector<int>& prototypes, const Eigen::Vector2d& xy,
                       double footprint, double road_clearance) {
  if (!claim(xy, 0.0, Eigen::Vector2d::Constant(footprint), road_clearance)) return;
  Plant plant;
  plant.prototype = prototypes[rng.integer(0, static_cast<int>(prototypes.size()) - 1)];
  plant.base = at_ground(xy);
  plant.yaw = static_cast<float>(rng.uniform(0.0, 2.0 * M_PI));
  plant.scale = static_cast<float>(rng.uniform(0.8, 1.25));
  plant.instance = world.new_instance();
  plant.sway_phase = static_cast<float>(rng.uniform(0.0, 2.0 * M_PI));
  world.plants.push_back(plant);
}

}  // namespace adaptive_lego_loam::sim
