#include "adaptive_lego_loam/sim/path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adaptive_lego_loam::sim {
namespace {

double wrap_angle(double angle) {
  return std::remainder(angle, 2.0 * M_PI);
}

double horizontal_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (b - a).head<2>().norm();
}

// Point at arc length s (horizontal) along a polyline with cumulative lengths `cumulative`.
Eigen::Vector3d polyline_at(const std::vector<Eigen::Vector3d>& polyline,
                            const std::vector<double>& cumulative, double s, std::size_t& hint) {
  while (hint + 2 < polyline.size() && cumulative[hint + 1] < s)
    ++hint;
  const double span = cumulative[hint + 1] - cumulative[hint];
  const double f = span > 0 ? std::clamp((s - cumulative[hint]) / span, 0.0, 1.0) : 0.0;
  return polyline[hint] + f * (polyline[hint + 1] - polyline[hint]);
}

// The two cell indices in one key (shifted as unsigned: a negative index's shift is undefined).
int64_t key_of(int64_t ix, int64_t iy) {
  return static_cast<int64_t>((static_cast<uint64_t>(ix) << 32) ^
                              (static_cast<uint64_t>(iy) & 0xFFFFFFFFull));
}

}  // namespace

Path::Path(const std::vector<Eigen::Vector3d>& input, bool closed, double spacing)
    : closed_(closed) {
  std::vector<Eigen::Vector3d> polyline;
  for (const Eigen::Vector3d& point : input) {
    if (polyline.empty() || horizontal_distance(polyline.back(), point) > 1e-6)
      polyline.push_back(point);
  }
  if (closed && polyline.size() > 1) polyline.push_back(polyline.front());
  std::vector<double> cumulative{0.0};
  for (std::size_t i = 1; i < polyline.size(); ++i)
    cumulative.push_back(cumulative.back() + horizontal_distance(polyline[i - 1], polyline[i]));
  length_ = cumulative.back();
  if (polyline.size() < 2 || length_ < 2.0 * spacing) {
    throw std::invalid_argument("path: fewer than two distinct points, or shorter than " +
                                std::to_string(2.0 * spacing) + " m");
  }
  const int segments = std::max(2, static_cast<int>(std::lround(length_ / spacing)));
  spacing_ = length_ / segments;
  const int count = closed ? segments : segments + 1;
  std::size_t hint = 0;
  for (int k = 0; k < count; ++k)
    points_.push_back(polyline_at(polyline, cumulative, k * spacing_, hint));

  const int n = static_cast<int>(points_.size());
  for (int k = 0; k < n; ++k) {
    const int prev = closed ? (k + n - 1) % n : std::max(k - 1, 0);
    const int next = closed ? (k + 1) % n : std::min(k + 1, n - 1);
    const Eigen::Vector3d delta = points_[next] - points_[prev];
    headings_.push_back(std::atan2(delta.y(), delta.x()));
    grades_.push_back(delta.z() / std::max(delta.head<2>().norm(), 1e-9));
  }
  for (int segment = 0; segment < segment_count(); ++segment) {
    const Eigen::Vector3d middle = 0.5 * (points_[segment] + points_[(segment + 1) % n]);
    segments_by_cell_[cell_key(middle.head<2>())].push_back(segment);
  }
}

int Path::segment_count() const {
  const int n = static_cast<int>(points_.size());
  return closed_ ? n : n - 1;
}

int64_t Path::cell_key(const Eigen::Vector2d& xy) const {
  return key_of(static_cast<int64_t>(std::floor(xy.x() / cell_size_)),
                static_cast<int64_t>(std::floor(xy.y() / cell_size_)));
}

Path::Frame Path::at(double s) const {
  const int n = static_cast<int>(points_.size());
  Frame frame;
  auto set_heading = [&frame](double heading) {
    frame.heading = heading;
    frame.forward = Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0);
    frame.left = Eigen::Vector3d(-std::sin(heading), std::cos(heading), 0.0);
  };
  if (!closed_ && (s < 0.0 || s > length_)) {
    const int end = s < 0.0 ? 0 : n - 1;
    const double beyond = s < 0.0 ? s : s - length_;
    set_heading(headings_[end]);
    frame.grade = grades_[end];
    frame.position = points_[end] + beyond * frame.forward;
    frame.position.z() += beyond * frame.grade;
    return frame;
  }
  if (closed_) {
    s = std::fmod(s, length_);
    if (s < 0.0) s += length_;
  }
  const int i = std::min(static_cast<int>(s / spacing_), segment_count() - 1);
  const int j = (i + 1) % n;
  const double f = s / spacing_ - i;
  frame.position = points_[i] + f * (points_[j] - points_[i]);
  set_heading(headings_[i] + f * wrap_angle(headings_[j] - headings_[i]));
  frame.grade = grades_[i] + f * (grades_[j] - grades_[i]);
  return frame;
}

void Path::project_on_segment(int segment, const Eigen::Vector2d& xy, Nearest& out) const {
  const int n = static_cast<int>(points_.size());
  const Eigen::Vector3d& a = points_[segment];
  const Eigen::Vector3d& b = points_[(segment + 1) % n];
  const Eigen::Vector2d ab = (b - a).head<2>();
  const double f = std::clamp((xy - a.head<2>()).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  const Eigen::Vector2d foot = a.head<2>() + f * ab;
  const Eigen::Vector2d offset = xy - foot;
  out.distance = offset.norm();
  out.lateral = (ab.x() * offset.y() - ab.y() * offset.x()) / ab.norm();
  out.s = (segment + f) * spacing_;
  out.height = a.z() + f * (b.z() - a.z());
}

bool Path::nearest(const Eigen::Vector2d& xy, double max_distance, Nearest& out) const {
  const int64_t cx = static_cast<int64_t>(std::floor(xy.x() / cell_size_));
  const int64_t cy = static_cast<int64_t>(std::floor(xy.y() / cell_size_));
  const int64_t rings = static_cast<int64_t>(std::ceil((max_distance + spacing_) / cell_size_));
  bool found = false;
  Nearest candidate;
  // Rings of cells around xy's cell, nearest first. A segment is filed under its middle's cell,
  // so one in ring r + 1 or beyond lies at least r * cell_size - spacing / 2 away.
  for (int64_t ring = 0; ring <= rings; ++ring) {
    for (int64_t ix = cx - ring; ix <= cx + ring; ++ix) {
      const bool edge_column = ix == cx - ring || ix == cx + ring;
      for (int64_t iy = cy - ring; iy <= cy + ring; iy += edge_column ? 1 : 2 * ring) {
        const auto cell = segments_by_cell_.find(key_of(ix, iy));
        if (cell != segments_by_cell_.end()) {
          for (int segment : cell->second) {
            project_on_segment(segment, xy, candidate);
            if (candidate.distance <= max_distance &&
                (!found || candidate.distance < out.distance)) {
              out = candidate;
              found = true;
            }
          }
        }
        if (ring == 0) break;
      }
    }
    if (found && out.distance <= ring * cell_size_ - spacing_) break;
  }
  return found;
}

std::vector<PathPiece> eased_curve(double curvature, double arc, double transition, int steps) {
  std::vector<PathPiece> pieces;
  for (int k = 0; k < steps; ++k)
    pieces.push_back({transition / steps, curvature * (k + 0.5) / steps});
  if (arc > 0.0) pieces.push_back({arc, curvature});
  for (int k = steps - 1; k >= 0; --k)
    pieces.push_back({transition / steps, curvature * (k + 0.5) / steps});
  return pieces;
}

std::vector<Eigen::Vector3d> trace_pieces(const std::vector<PathPiece>& pieces, double sample) {
  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::Zero()};
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double heading = 0.0;
  for (const PathPiece& piece : pieces) {
    const int steps = std::max(1, static_cast<int>(std::ceil(piece.length / sample)));
    const double step = piece.length / steps;
    for (int k = 0; k < steps; ++k) {
      const double turn = piece.curvature * step;
      if (std::abs(turn) < 1e-12) {
        position += step * Eigen::Vector2d(std::cos(heading), std::sin(heading));
      } else {  // exact arc
        const double radius = 1.0 / piece.curvature;
        position += radius * Eigen::Vector2d(std::sin(heading + turn) - std::sin(heading),
                                             std::cos(heading) - std::cos(heading + turn));
      }
      heading += turn;
      points.emplace_back(position.x(), position.y(), 0.0);
    }
  }
  return points;
}

}  // namespace adaptive_lego_loam::sim
