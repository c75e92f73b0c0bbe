// Synthetic paths: an eased curve turns as much as its arc plus one transition would, in small
// steps of curvature, and tracing samples it as finely as asked.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/sim/path.h"

using namespace adaptive_lego_loam::sim;

TEST(SimPath, AnEasedCurveTurnsInSmallStepsOfCurvature) {
  const double curvature = 1.0 / 500.0;
  const std::vector<PathPiece> pieces = eased_curve(curvature, 150.0, 60.0, 12);
  ASSERT_EQ(pieces.size(), 25u);
  double turned = 0.0, length = 0.0, previous = 0.0, largest_step = 0.0;
  for (const PathPiece& piece : pieces) {
    turned += piece.curvature * piece.length;
    length += piece.length;
    largest_step = std::max(largest_step, std::abs(piece.curvature - previous));
    previous = piece.curvature;
  }
  EXPECT_NEAR(turned, curvature * (150.0 + 60.0), 1e-12);
  EXPECT_NEAR(length, 150.0 + 2.0 * 60.0, 1e-9);
  EXPECT_LE(largest_step, 1.5 * curvature / 12.0);  // half a step in, full steps after
  // Traced every 5 cm, the heading at the end is the turn.
  const std::vector<Eigen::Vector3d> points = trace_pieces(pieces, 0.05);
  EXPECT_GE(points.size(), static_cast<std::size_t>(length / 0.05));
  const Eigen::Vector3d last = points.back() - points[points.size() - 2];
  EXPECT_NEAR(std::atan2(last.y(), last.x()), turned, 1e-3);
  // A quarter turn of a robot with no arc at full curvature: two transitions.
  double quarter = 0.0;
  for (const PathPiece& piece : eased_curve(1.0 / 0.8, 0.0, 0.5 * M_PI * 0.8, 4))
    quarter += piece.curvature * piece.length;
  EXPECT_NEAR(quarter, 0.5 * M_PI, 1e-12);
}
