#include "paths.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adaptive_lego_loam::sim {
namespace {

constexpr double kUrbanTurnRadius = 14.0;

}  // namespace

std::vector<PathPiece> open_pieces(ScenarioKind kind, double length, double lead, Rng& rng) {
  std::vector<PathPiece> pieces;
  double total = 0.0;
  auto add = [&](double piece_length, double curvature) {
    pieces.push_back({piece_length, curvature});
    total += piece_length;
  };
  switch (kind) {
    case ScenarioKind::kTunnel:
    case ScenarioKind::kCorridor:
      add(length, 0.0);
      break;
    case ScenarioKind::kHighway:
      add(lead + rng.uniform(300.0, 800.0), 0.0);
      while (total < length) {
        const double radius = rng.uniform(1500.0, 3000.0);
        const double angle = rng.uniform(3.0, 10.0) * M_PI / 180.0;
        add(radius * angle, rng.sign() / radius);
        add(rng.uniform(400.0, 1200.0), 0.0);
      }
      break;
    case ScenarioKind::kVegetation: {
      add(lead + rng.uniform(10.0, 40.0), 0.0);
      double turn_sign = rng.sign();
      while (total < length) {
        const double radius = rng.uniform(35.0, 120.0);
        const double angle = rng.uniform(15.0, 70.0) * M_PI / 180.0;
        add(radius * angle, turn_sign / radius);
        add(rng.uniform(15.0, 70.0), 0.0);
        turn_sign = rng.chance(0.7) ? -turn_sign : turn_sign;
      }
      break;
    }
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      add(lead + rng.uniform(40.0, 120.0), 0.0);
      while (total < length) {
        add(0.5 * M_PI * kUrbanTurnRadius, rng.sign() / kUrbanTurnRadius);
        add(rng.uniform(60.0, 160.0), 0.0);
      }
      break;
  }
  // Only as long as needed: terrain and objects are built along all of it.
  while (total - pieces.back().length >= length) {
    total -= pieces.back().length;
    pieces.pop_back();
  }
  pieces.back().length -= total - length;
  return pieces;
}

std::vector<PathPiece> loop_pieces(double length) {
  const double r = kUrbanTurnRadius;
  const double sides = (length - 2.0 * M_PI * r + 8.0 * r) / 2.0;  // a + b
  const double a = sides * 0.6, b = sides * 0.4;
  std::vector<PathPiece> pieces;
  for (int corner = 0; corner < 4; ++corner) {
    pieces.push_back({(corner % 2 == 0 ? a : b) - 2.0 * r, 0.0});
    pieces.push_back({0.5 * M_PI * r, 1.0 / r});
  }
  return pieces;
}

std::shared_ptr<const Path> synthetic_path(const std::vector<PathPiece>& pieces, bool closed,
                                           const HeightField& hills) {
  std::vector<Eigen::Vector3d> points = trace_pieces(pieces);
  if (closed) points.pop_back();  // the last point is the first again
  for (Eigen::Vector3d& point : points)
    point.z() = hills.at(point.head<2>());
  return std::make_shared<Path>(points, closed);
}

std::shared_ptr<const Path> recorded_path(const std::vector<Eigen::Isometry3d>& sensor_poses,
                                          double sensor_height, double ego_lateral, double lead) {
  std::vector<Eigen::Vector3d> centre;
  for (const Eigen::Isometry3d& pose : sensor_poses) {
    const Eigen::Vector3d forward = pose.linear().col(0);
    const Eigen::Vector3d left = Eigen::Vector3d(-forward.y(), forward.x(), 0.0).normalized();
    const Eigen::Vector3d point =
        pose * Eigen::Vector3d(0.0, 0.0, -sensor_height) - ego_lateral * left;
    if (centre.empty() || (point - centre.back()).head<2>().norm() >= 0.5) centre.push_back(point);
  }
  auto heading_of = [](const Eigen::Isometry3d& pose) -> Eigen::Vector3d {
    const Eigen::Vector3d forward = pose.linear().col(0);
    return Eigen::Vector3d(forward.x(), forward.y(), 0.0).normalized();
  };
  const Eigen::Vector3d first_forward =
      centre.size() > 1 ? Eigen::Vector3d((centre[1] - centre[0]).head<2>().normalized().x(),
                                          (centre[1] - centre[0]).head<2>().normalized().y(), 0.0)
                        : heading_of(sensor_poses.front());
  const Eigen::Vector3d last_forward =
      centre.size() > 1
          ? Eigen::Vector3d((centre.back() - centre[centre.size() - 2]).head<2>().normalized().x(),
                            (centre.back() - centre[centre.size() - 2]).head<2>().normalized().y(),
                            0.0)
          : heading_of(sensor_poses.back());
  std::vector<Eigen::Vector3d> points;
  for (double back = lead; back >= 1.0; back -= 1.0)
    points.push_back(centre.front() - back * first_forward);
  points.insert(points.end(), centre.begin(), centre.end());
  for (double ahead = 1.0; ahead <= lead; ahead += 1.0)
    points.push_back(centre.back() + ahead * last_forward);
  return std::make_shared<Path>(points, false);
}

}  // namespace adaptive_lego_loam::sim
