#pragma once
// The road's centreline: the path the ego vehicle drives and the scene is built along.

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace adaptive_lego_loam::sim {

class Path {
 public:
  // `points` lie on the road surface in driving order (at least two, not all the same). They are
  // resampled every `spacing` metres of arc length. A closed path joins its last point to its
  // first.
  Path(const std::vector<Eigen::Vector3d>& points, bool closed, double spacing = 1.0);

  double length() const { return length_; }
  double spacing() const { return spacing_; }
  bool closed() const { return closed_; }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }

  struct Frame {
    Eigen::Vector3d position;  // on the road surface
    Eigen::Vector3d forward;   // unit, horizontal
    Eigen::Vector3d left;      // unit, horizontal
    double heading = 0.0;      // rad, of `forward` from the x axis
    double grade = 0.0;        // dz per metre along the path
  };
  // At arc length s: wrapped on a closed path, extended straight past the ends of an open one.
  Frame at(double s) const;

  struct Nearest {
    double s = 0.0;
    double lateral = 0.0;   // signed offset from the centreline, positive to the left
    double height = 0.0;    // of the centreline there
    double distance = 0.0;  // horizontal, = |lateral| except beyond the ends
  };
  // The closest centreline point horizontally within `max_distance`; false when there is none.
  bool nearest(const Eigen::Vector2d& xy, double max_distance, Nearest& out) const;

 private:
  int64_t cell_key(const Eigen::Vector2d& xy) const;
  int segment_count() const;
  void project_on_segment(int segment, const Eigen::Vector2d& xy, Nearest& out) const;

  std::vector<Eigen::Vector3d> points_;  // resampled
  std::vector<double> headings_;         // per point, smoothed over its two segments
  std::vector<double> grades_;
  double spacing_ = 1.0;
  double length_ = 0.0;
  bool closed_ = false;
  double cell_size_ = 16.0;
  std::unordered_map<int64_t, std::vector<int>> segments_by_cell_;
};

// Straight pieces and circular arcs, joined tangentially, in the horizontal plane.
struct PathPiece {
  double length = 0.0;     // m
  double curvature = 0.0;  // 1/m, positive turns left
};

// A curve whose curvature ramps up in `steps` equal steps over `transition` m, holds
// `curvature` for `arc` m and ramps down again (a clothoid's transition, approximately), so that
// the lateral acceleration of a vehicle on it changes gradually. It turns by
// curvature x (arc + transition).
std::vector<PathPiece> eased_curve(double curvature, double arc, double transition, int steps);

// Samples the pieces every `step` m (or a little less, to end each piece on a sample) starting at
// the origin heading along x; z stays 0 (heights are set by the caller).
std::vector<Eigen::Vector3d> trace_pieces(const std::vector<PathPiece>& pieces, double step = 1.0);

}  // namespace adaptive_lego_loam::sim
