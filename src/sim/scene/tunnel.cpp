#include "tunnel.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/sim/objects.h"
#include "roadside_objects.h"

namespace adaptive_lego_loam::sim {
namespace {

// Furniture of a road tunnel, from how they are built (docs/simulator.md, Scenes): luminaires
// in a line along the vault every 25 m (issue 44's spacing; interior-zone lighting is commonly
// 10-25 m apart), 1.5 x 0.4 x 0.15 m housings;
constexpr double kLampSpacing = 25.0;
// emergency stations in niches at most 150 m apart (EU Directive 2004/54/EC on tunnel safety,
// for new tunnels), 2.5 m wide, 1.2 m deep and 2.4 m high behind the ledge;
constexpr double kNicheSpacing = 150.0, kNicheWidth = 2.5, kNicheDepth = 1.2, kNicheHeight = 2.4;
// escape-route signs on both side walls at most 25 m apart, 1.0-1.5 m above the walkway (the
// same Directive);
constexpr double kEscapeSignSpacing = 25.0;
// jet fans hung in pairs under the vault, 1.1 m across and 5 m long with their silencers, the
// pairs 150-300 m apart;
constexpr double kFanRadius = 0.55, kFanLength = 5.0;
// lane-control signals over each lane, 0.9 m square, every 250-500 m; a cable tray along one
// wall, 0.4 m wide at 3.6 m.
constexpr double kSignalSize = 0.9;
// The curve eases in and out over 60 m, as a clothoid of parameter A = sqrt(60 R) would (R/5 to
// R/3 at these radii).
constexpr double kCurveTransition = 60.0;
// A driver brakes and pulls away with the acceleration ramping up and down over a second.
constexpr double kSpeedRamp = 1.0;

// The tunnel's wall and vault on one side, as (left offset, height above the centreline) from
// the ledge up to the crown: the other-structure pieces of the scenario's cross-section.
std::vector<Eigen::Vector2d> wall_outline(const ScenarioParams& p, double side) {
  std::vector<Eigen::Vector2d> outline;
  for (const CrossSectionPiece& piece : road_cross_section(p)) {
    if (piece.semantic != SemanticClass::kOtherStructure || (piece.d0 + piece.d1) * side <= 0.0)
      continue;
    if (outline.empty()) outline.emplace_back(piece.d0, piece.z0);
    outline.emplace_back(piece.d1, piece.z1);
  }
  return outline;
}

// Height of the vault's underside (above the centreline) at `offset` m from the centreline.
double vault_height(const std::vector<Eigen::Vector2d>& outline, double offset) {
  const double d = std::abs(offset);
  for (std::size_t i = 1; i < outline.size(); ++i) {
    const double d0 = std::abs(outline[i - 1].x()), d1 = std::abs(outline[i].x());
    if (d0 == d1 || d > d0 || d < d1) continue;  // the vault runs from the wall in to the crown
    return outline[i - 1].y() + (outline[i].y() - outline[i - 1].y()) * (d0 - d) / (d0 - d1);
  }
  return outline.back().y();
}

// The lowest the vault gets over [offset - half, offset + half].
double vault_clearance(const std::vector<Eigen::Vector2d>& outline, double offset, double half) {
  return std::min(vault_height(outline, offset - half), vault_height(outline, offset + half));
}

// A point `offset` m left of the centreline at arc length s, `height` m above it.
Eigen::Vector3f at(const Path& path, double s, double offset, double height) {
  const Path::Frame f = path.at(s);
  Eigen::Vector3d point = f.position + offset * f.left;
  point.z() += height;
  return point.cast<float>();
}

// A box whose bottom face is centred `offset` m left of the centreline at s, `height` m up,
// turned along the path (size: along, across, up).
void add_box_at(Layout& l, double s, double offset, double height, const Eigen::Vector3f& size,
                uint32_t surface) {
  const Eigen::Vector3f base = at(l.path, s, offset, height);
  add_box(l.world.tile_at(base), yaw_pose(base, static_cast<float>(l.path.at(s).heading)), size,
          surface);
}

// A niche in the wall on `side` centred at s: back, sides, top and floor.
void add_niche(Layout& l, double s, double side, double wall, double floor, uint32_t surface) {
  const double s0 = s - 0.5 * kNicheWidth, s1 = s + 0.5 * kNicheWidth;
  const double front = side * wall, back = side * (wall + kNicheDepth);
  const double top = floor + kNicheHeight;
  GeometrySet& set = l.world.tile_at(at(l.path, s, front, floor));
  auto p = [&](double along, double offset, double height) {
    return at(l.path, along, offset, height);
  };
  set.add_quad(p(s0, back, floor), p(s1, back, floor), p(s1, back, top), p(s0, back, top), surface);
  for (double end : {s0, s1}) {
    set.add_quad(p(end, front, floor), p(end, back, floor), p(end, back, top), p(end, front, top),
                 surface);
  }
  set.add_quad(p(s0, front, top), p(s1, front, top), p(s1, back, top), p(s0, back, top), surface);
  set.add_quad(p(s0, front, floor), p(s1, front, floor), p(s1, back, floor), p(s0, back, floor),
               surface);
}

// Walls and vault from the portal to the path's end; on the right the wall has a niche every
// 150 m (tunnel_furniture). Returns the niches' centres.
std::vector<double> build_walls(Layout& l, const TunnelPlan& plan, uint32_t wall) {
  const ScenarioParams& p = l.p;
  const double end = l.length(), floor = p.curb_height,
               width = p.road_half_width + p.sidewalk_width;
  std::vector<double> niches;
  if (p.tunnel_furniture) {
    for (double s = plan.portal_s + l.rng.uniform(40.0, kNicheSpacing); s + kNicheWidth < end;
         s += kNicheSpacing)
      niches.push_back(s);
  }
  for (double side : {-1.0, 1.0}) {
    std::vector<Eigen::Vector2d> outline = wall_outline(p, side);
    if (side > 0.0 || niches.empty()) {
      sweep_outline(l, plan.portal_s, end, 0.0, outline, false, wall);
      continue;
    }
    // Above the niches the wall goes on; below their top it stops at each.
    const Eigen::Vector2d split(side * width, floor + kNicheHeight);
    outline.front() = split;
    sweep_outline(l, plan.portal_s, end, 0.0, outline, false, wall);
    const std::vector<Eigen::Vector2d> lower = {{side * width, floor}, split};
    double from = plan.portal_s;
    for (double niche : niches) {
      sweep_outline(l, from, niche - 0.5 * kNicheWidth, 0.0, lower, false, wall);
      add_niche(l, niche, side, width, floor,
                l.world.add_surface(SemanticClass::kOtherStructure, l.world.new_instance(), 0.5f));
      from = niche + 0.5 * kNicheWidth;
    }
    sweep_outline(l, from, end, 0.0, lower, false, wall);
  }
  return niches;
}

// The head wall around the portal, facing the approach, as wide as the cutting at its top.
void build_portal(Layout& l, const TunnelPlan& plan, uint32_t surface) {
  const ScenarioParams& p = l.p;
  const double s = plan.portal_s, top = plan.cutting_depth;
  const double width = p.road_half_width + p.sidewalk_width;
  const double reach = width + 1.0 + 1.5 * top + 2.0;  // past the cutting's slopes
  GeometrySet& set = l.world.tile_at(at(l.path, s, 0.0, 0.0));
  auto p_at = [&](double offset, double height) { return at(l.path, s, offset, height); };
  for (double side : {-1.0, 1.0}) {
    set.add_quad(p_at(side * width, -0.5), p_at(side * reach, -0.5), p_at(side * reach, top),
                 p_at(side * width, top), surface);
    const std::vector<Eigen::Vector2d> outline = wall_outline(p, side);
    for (std::size_t i = 1; i < outline.size(); ++i) {  // above the wall and the vault
      const Eigen::Vector2d& a = outline[i - 1];
      const Eigen::Vector2d& b = outline[i];
      if (a.x() == b.x()) continue;
      set.add_quad(p_at(a.x(), a.y()), p_at(b.x(), b.y()), p_at(b.x(), top), p_at(a.x(), top),
                   surface);
    }
  }
}

// True when s lies within `margin` of one of `places`.
bool near(const std::vector<double>& places, double s, double margin) {
  return std::any_of(places.begin(), places.end(),
                     [&](double place) { return std::abs(place - s) < margin; });
}

// Along the vault, except where a jet fan or a lane signal hangs.
void add_lamps(Layout& l, const TunnelPlan& plan, const std::vector<Eigen::Vector2d>& vault,
               const std::vector<double>& fans, const std::vector<double>& signals) {
  const double offset = l.rng.uniform(-2.5, 2.5), depth = 0.15;
  const double height = vault_clearance(vault, offset, 0.2) - depth - 0.02;
  for (double s = plan.portal_s + l.rng.uniform(5.0, kLampSpacing); s < l.length();
       s += kLampSpacing) {
    if (near(fans, s, 0.5 * kFanLength + 1.0) || near(signals, s, 1.5)) continue;
    add_box_at(l, s, offset, height, Eigen::Vector3f(1.5f, 0.4f, static_cast<float>(depth)),
               l.world.add_surface(SemanticClass::kOtherObject, l.world.new_instance(), 0.6f));
  }
}

std::vector<double> add_jet_fans(Layout& l, const TunnelPlan& plan,
                                 const std::vector<Eigen::Vector2d>& vault) {
  std::vector<double> pairs;
  for (double s = plan.portal_s + l.rng.uniform(60.0, 200.0); s + kFanLength < l.length();
       s += l.rng.uniform(150.0, 300.0)) {
    pairs.push_back(s);
    for (double offset : {-1.1, 1.1}) {
      const double axis = vault_clearance(vault, offset, kFanRadius) - 0.3 - kFanRadius;
      const Eigen::Vector3f a = at(l.path, s - 0.5 * kFanLength, offset, axis);
      const Eigen::Vector3f b = at(l.path, s + 0.5 * kFanLength, offset, axis);
      l.world.tile_at(a).add_prism(
          a, b, static_cast<float>(kFanRadius), 16,
          l.world.add_surface(SemanticClass::kOtherObject, l.world.new_instance(), 0.5f));
    }
  }
  return pairs;
}

std::vector<double> add_lane_signals(Layout& l, const TunnelPlan& plan,
                                     const std::vector<Eigen::Vector2d>& vault,
                                     const std::vector<double>& fans) {
  const float size = static_cast<float>(kSignalSize);
  std::vector<double> signals;
  for (double s = plan.portal_s + l.rng.uniform(100.0, 300.0); s < l.length();
       s += l.rng.uniform(250.0, 500.0)) {
    if (near(fans, s, 0.5 * kFanLength + 3.0)) continue;
    signals.push_back(s);
    const uint16_t instance = l.world.new_instance();
    const uint32_t surface = l.world.add_surface(SemanticClass::kTrafficSign, instance, 0.9f);
    for (double offset : {-2.25, 2.25}) {
      const double roof = vault_clearance(vault, offset, 0.5 * kSignalSize);
      const double bottom = roof - 0.5 - kSignalSize;
      add_box_at(l, s, offset, bottom, Eigen::Vector3f(0.35f, size, size), surface);
      const Eigen::Vector3f hanger = at(l.path, s, offset, bottom + kSignalSize);
      l.world.tile_at(hanger).add_prism(hanger, at(l.path, s, offset, roof + 0.05), 0.03f, 8,
                                        surface);
    }
  }
  return signals;
}

// Escape-route signs on both walls, an emergency-station sign over each niche.
void add_wall_signs(Layout& l, const TunnelPlan& plan, const std::vector<double>& niches) {
  const ScenarioParams& p = l.p;
  const double width = p.road_half_width + p.sidewalk_width, walkway = p.curb_height;
  for (double side : {-1.0, 1.0}) {
    for (double s = plan.portal_s + l.rng.uniform(5.0, kEscapeSignSpacing); s < l.length();
         s += kEscapeSignSpacing) {
      if (near(niches, s, 0.5 * kNicheWidth + 1.0)) continue;
      add_box_at(l, s, side * (width - 0.04), walkway + 1.05, Eigen::Vector3f(0.8f, 0.08f, 0.4f),
                 l.world.add_surface(SemanticClass::kTrafficSign, l.world.new_instance(), 0.9f));
    }
  }
  for (double niche : niches) {
    add_box_at(l, niche, -(width - 0.04), walkway + kNicheHeight + 0.3,
               Eigen::Vector3f(0.6f, 0.08f, 0.6f),
               l.world.add_surface(SemanticClass::kTrafficSign, l.world.new_instance(), 0.9f));
  }
}

void add_cable_tray(Layout& l, const TunnelPlan& plan) {
  const double side = 1.0, wall = side * (l.p.road_half_width + l.p.sidewalk_width);
  const double low = 3.6, high = 3.7, reach = -side * 0.4;
  sweep_outline(l, plan.portal_s, l.length(), wall,
                {{0.0, low}, {reach, low}, {reach, high}, {0.0, high}}, false,
                l.world.add_surface(SemanticClass::kOtherStructure, l.world.new_instance(), 0.4f));
}

// The open road before the portal: guard rails, shrubs and trees in the fields and on the
// cutting's slopes, two signs.
void layout_approach(Layout& l, const TunnelPlan& plan) {
  const ScenarioParams& p = l.p;
  const double w = p.road_half_width, end = plan.portal_s - 1.0;
  for (double side : {-1.0, 1.0}) {
    if (p.guard_rails) add_guard_rail(l, side * (w + 0.3), side, 0.0, end);
    for (double s = l.rng.uniform(0.0, 5.0); s < end; s += l.step(p.bushes_per_100m))
      l.add_plant(l.bush_prototypes, l.beside(s, side * (w + l.rng.uniform(3.0, 30.0))), 0.6,
                  w + 1.5);
    for (double s = l.rng.uniform(0.0, 20.0); s < end; s += l.step(p.trees_per_100m))
      l.add_plant(l.tree_prototypes, l.beside(s, side * (w + l.rng.uniform(8.0, 40.0))), 0.6,
                  w + 6.0);
  }
  for (double ahead : {l.rng.uniform(20.0, 60.0), l.rng.uniform(80.0, 140.0)}) {
    const double s = plan.portal_s - ahead;
    const Path::Frame f = l.path.at(s);
    const Eigen::Vector2d xy = l.beside(s, -(w + 1.2));
    if (s < 0.0 || !l.claim(xy, f.heading, Eigen::Vector2d(0.3, 0.3), 0.0)) continue;
    const uint16_t instance = l.world.new_instance();
    const Eigen::Vector3f base = l.at_ground(xy);
    add_sign(l.world.tile_at(base), base, (-f.forward).cast<float>(),
             l.world.add_surface(SemanticClass::kPole, instance, 0.5f),
             l.world.add_surface(SemanticClass::kTrafficSign, instance, 0.9f));
  }
}

}  // namespace

TunnelPlan plan_tunnel(const ScenarioParams& p, double ego_start_s, Rng& rng) {
  TunnelPlan plan;
  plan.portal_s = ego_start_s + rng.uniform(90.0, 120.0);
  plan.cutting_depth = rng.uniform(10.0, 14.0);
  const double start = plan.portal_s + rng.uniform(50.0, 150.0);
  // Road tunnels curve gently: radii of 500-1500 m keep the sight distance at 60-80 km/h.
  const double radius = rng.uniform(500.0, 1500.0), length = rng.uniform(150.0, 300.0);
  const double sign = rng.sign();
  if (p.tunnel_curve) {
    plan.curve_start_s = start;
    plan.curve_length = length;
    plan.curvature = sign / radius;
  }
  return plan;
}

std::vector<PathPiece> tunnel_pieces(const TunnelPlan& plan, double length) {
  std::vector<PathPiece> pieces{{plan.curve_start_s, 0.0}};
  if (plan.curvature != 0.0) {
    for (const PathPiece& piece :
         eased_curve(plan.curvature, plan.curve_length, kCurveTransition, 12))
      pieces.push_back(piece);
  }
  // As long as the drive needs: the last piece ends there, later ones are left out.
  std::vector<PathPiece> kept;
  double total = 0.0;
  for (const PathPiece& piece : pieces) {
    if (total >= length) break;
    kept.push_back({std::min(piece.length, length - total), piece.curvature});
    total += kept.back().length;
  }
  if (total < length) kept.push_back({length - total, 0.0});
  return kept;
}

std::vector<SpeedChange> tunnel_speed_changes(const ScenarioParams& p, const SpeedProfile& cruise,
                                              double entry_m, Rng& rng) {
  const double brake_at = cruise.time_at_distance(entry_m) + rng.uniform(2.0, 4.0);
  const double deceleration = rng.uniform(0.5, 1.0), slow_for = rng.uniform(2.0, 4.0);
  const double acceleration = rng.uniform(0.5, 1.0);
  const double change = p.cruise_speed_mps - p.slow_speed_mps;
  if (p.slow_speed_mps <= 0.0 || change <= 0.0) return {};
  const SpeedChange brake{brake_at, -change, deceleration, kSpeedRamp};
  const SpeedChange pull_away{brake.end_time() + slow_for, change, acceleration, kSpeedRamp};
  return {brake, pull_away};
}

std::vector<Berm> tunnel_cutting(const ScenarioParams& p, const TunnelPlan& plan,
                                 double path_length) {
  std::vector<Berm> berms;
  for (double side : {-1.0, 1.0}) {
    Berm berm;
    berm.ramp = 100.0;
    berm.s0 = plan.portal_s - berm.ramp;
    berm.s1 = path_length + berm.ramp;
    berm.side = side;
    berm.toe = p.road_half_width + p.sidewalk_width + 1.0;
    berm.height = plan.cutting_depth;
    berm.crest = 60.0;  // the level of the land above, which stays up
    berms.push_back(berm);
  }
  return berms;
}

std::vector<CrossSectionPiece> tunnel_road_section(const ScenarioParams& p) {
  std::vector<CrossSectionPiece> section;
  for (const CrossSectionPiece& piece : road_cross_section(p)) {
    if (piece.semantic != SemanticClass::kOtherStructure) section.push_back(piece);
  }
  return section;
}

std::shared_ptr<const Path> tunnel_approach(const Path& path, const TunnelPlan& plan) {
  const std::size_t count =
      std::min(path.points().size(),
               static_cast<std::size_t>(std::ceil((plan.portal_s + 20.0) / path.spacing())) + 1);
  return std::make_shared<Path>(
      std::vector<Eigen::Vector3d>(path.points().begin(), path.points().begin() + count), false,
      path.spacing());
}

void layout_tunnel(Layout& l, const TunnelPlan& plan) {
  const uint32_t wall = l.world.add_surface(SemanticClass::kOtherStructure, 0, 0.5f);
  build_portal(l, plan, wall);
  const std::vector<double> niches = build_walls(l, plan, wall);
  layout_approach(l, plan);
  if (!l.p.tunnel_furniture) return;
  const std::vector<Eigen::Vector2d> vault = wall_outline(l.p, 1.0);
  const std::vector<double> fans = add_jet_fans(l, plan, vault);
  const std::vector<double> signals = add_lane_signals(l, plan, vault, fans);
  add_lamps(l, plan, vault, fans, signals);
  add_wall_signs(l, plan, niches);
  add_cable_tray(l, plan);
}

}  // namespace adaptive_lego_loam::sim
