#pragma once
// Part of the scene generator (scene_generator.cpp): a road tunnel entered from open road. The
// approach runs through fields between guard rails into a cutting that deepens toward the
// portal's head wall; inside, the ledges, walls and vault of the tunnel scenario's cross-section
// and, unless it is bare, the furniture of a real road tunnel and a gentle curve.

#include <memory>
#include <vector>

#include "adaptive_lego_loam/sim/path.h"
#include "adaptive_lego_loam/sim/speed_profile.h"
#include "placement.h"

namespace adaptive_lego_loam::sim {

struct TunnelPlan {
  double portal_s = 0.0;  // arc length of the portal along the path
  // The curve inside the tunnel (curvature 0: none), from curve_start_s for curve_length m.
  double curve_start_s = 0.0, curve_length = 0.0, curvature = 0.0;
  double cutting_depth = 12.0;  // of the cutting at the portal: the head wall's height
};

// The portal 90-120 m ahead of the ego vehicle's start at `ego_start_s`.
TunnelPlan plan_tunnel(const ScenarioParams& p, double ego_start_s, Rng& rng);

// The path's pieces, `length` m in all: straight to the curve, the curve, straight on.
std::vector<PathPiece> tunnel_pieces(const TunnelPlan& plan, double length);

// Braking to the scenario's slow speed 2-4 s after the portal, 2-4 s at that speed, then back to
// the cruise speed; `entry_m`: how far the drive goes before the portal at the `cruise` profile.
std::vector<SpeedChange> tunnel_speed_changes(const ScenarioParams& p, const SpeedProfile& cruise,
                                              double entry_m, Rng& rng);

// The cutting's slopes on both sides: they rise over the last 100 m before the portal and stay
// up over the tunnel (the terrain follows them).
std::vector<Berm> tunnel_cutting(const ScenarioParams& p, const TunnelPlan& plan,
                                 double path_length);

// What build_road sweeps along the path: the carriageway everywhere and, from the portal on, the
// ledges (the walls and vault are built by layout_tunnel, around the niches).
std::vector<CrossSectionPiece> tunnel_road_section(const ScenarioParams& p);

// The path's stretch from its start to a little past the portal: the terrain is built along it.
std::shared_ptr<const Path> tunnel_approach(const Path& path, const TunnelPlan& plan);

// Walls, vault, the portal's head wall and (tunnel_furniture) lamps, niches, signs, jet fans and
// a cable tray; on the approach guard rails, shrubs, trees and signs.
void layout_tunnel(Layout& l, const TunnelPlan& plan);

}  // namespace adaptive_lego_loam::sim
