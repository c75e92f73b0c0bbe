#include "adaptive_lego_loam/sim/terrain.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam::sim {
namespace {

constexpr double kGridCell = 16.0;
constexpr double kTerrainStep = 1.0;
constexpr double kCoveredDepth = -0.3;  // terrain under the road: out of sight

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

HeightField::HeightField(Rng& rng, double amplitude, double wavelength, int count) {
  for (int i = 0; i < count; ++i) {
    const double direction = rng.uniform(0.0, 2.0 * M_PI);
    const double length = wavelength * rng.uniform(0.7, 1.4);
    const double k = 2.0 * M_PI / length;
    waves_.push_back({Eigen::Vector2d(k * std::cos(direction), k * std::sin(direction)),
                      amplitude / count, rng.uniform(0.0, 2.0 * M_PI)});
  }
}

double HeightField::at(const Eigen::Vector2d& xy) const {
  double height = 0.0;
  for (const Wave& wave : waves_)
    height += wave.amplitude * std::sin(wave.wave_vector.dot(xy) + wave.phase);
  return height;
}

std::vector<CrossSectionPiece> road_cross_section(const ScenarioParams& s) {
  const double w = s.road_half_width;
  const float asphalt = s.kind == ScenarioKind::kVegetation ? 0.15f : 0.2f;
  std::vector<CrossSectionPiece> section{{-w, 0.0, w, 0.0, SemanticClass::kRoad, asphalt}};
  auto marking = [&](double d, double on, double period) {
    // 5 mm above the asphalt: painted lines return more light.
    section.push_back({d - 0.075, 0.005, d + 0.075, 0.005, SemanticClass::kRoad, 0.7f, on, period});
  };
  switch (s.kind) {
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      marking(0.0, 3.0, 6.0);
      break;
    case ScenarioKind::kHighway:
      for (double lane : {3.75, 7.5}) {
        marking(0.5 + lane, 6.0, 18.0);
        marking(-0.5 - lane, 6.0, 18.0);
      }
      marking(w - 0.6, 1.0, 0.0);
      marking(-w + 0.6, 1.0, 0.0);
      break;
    case ScenarioKind::kTunnel:
      marking(0.0, 6.0, 18.0);
      break;
    case ScenarioKind::kVegetation:
    case ScenarioKind::kCorridor:
      break;
  }
  if (s.sidewalk_width > 0.0) {
    const double top = s.curb_height, outer = w + s.sidewalk_width;
    for (double side : {-1.0, 1.0}) {
      section.push_back({side * w, 0.0, side * w, top, SemanticClass::kSidewalk, 0.35f});
      section.push_back({side * w, top, side * outer, top, SemanticClass::kSidewalk, 0.35f});
    }
  }
  if (s.tunnel) {
    // Vertical walls to 4.5 m, then an elliptic vault to 7 m over the centreline.
    const double wall = w + s.sidewalk_width, spring = 4.5, crown = 7.0;
    constexpr int kVaultPieces = 6;
    for (double side : {-1.0, 1.0}) {
      section.push_back(
          {side * wall, s.curb_height, side * wall, spring, SemanticClass::kOtherStructure, 0.5f});
      for (int i = 0; i < kVaultPieces; ++i) {
        const double a0 = 0.5 * M_PI * i / kVaultPieces, a1 = 0.5 * M_PI * (i + 1) / kVaultPieces;
        section.push_back({side * wall * std::cos(a0), spring + (crown - spring) * std::sin(a0),
                           side * wall * std::cos(a1), spring + (crown - spring) * std::sin(a1),
                           SemanticClass::kOtherStructure, 0.5f});
      }
    }
  }
  return section;
}

std::vector<CrossSectionPiece> side_street_cross_section(const SideStreet& street) {
  const double w = street.half_width, top = street.curb_height, outer = street.outer();
  std::vector<CrossSectionPiece> section{
      {-w, 0.0, w, 0.0, SemanticClass::kRoad, 0.2f},
      {-0.075, 0.005, 0.075, 0.005, SemanticClass::kRoad, 0.7f, 3.0, 6.0}};
  for (double side : {-1.0, 1.0}) {
    section.push_back({side * w, 0.0, side * w, top, SemanticClass::kSidewalk, 0.35f});
    section.push_back({side * w, top, side * outer, top, SemanticClass::kSidewalk, 0.35f});
  }
  return section;
}

TerrainModel::TerrainModel(const Path& path, const ScenarioParams& s, HeightField hills,
                           HeightField relief, bool path_follows_hills, double reach)
    : path_(path),
      hills_(std::move(hills)),
      relief_(std::move(relief)),
      path_follows_hills_(path_follows_hills) {
  const double w = s.road_half_width;
  switch (s.kind) {
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
    case ScenarioKind::kTunnel: {
      const double outer = w + s.sidewalk_width, top = s.curb_height;
      // Just under the sidewalk, then level with its outer edge.
      profile_ = {{w - 0.6, kCoveredDepth},
                  {w + 0.4, top - 0.05},
                  {outer - 0.3, top - 0.05},
                  {outer + 0.2, top}};
      covered_until_ = outer - 0.3;
      blend_start_ = outer + 3.0;
      blend_end_ = outer + 30.0;
      break;
    }
    case ScenarioKind::kHighway:
      // Verge, ditch, then the fields.
      profile_ = {{w - 0.6, kCoveredDepth},
                  {w + 0.2, -0.03},
                  {w + 2.0, -0.12},
                  {w + 5.0, -0.9},
                  {w + 8.0, -0.1}};
      covered_until_ = w - 0.6;
      blend_start_ = w + 8.0;
      blend_end_ = w + 40.0;
      break;
    case ScenarioKind::kVegetation:
    case ScenarioKind::kCorridor:
      profile_ = {{w - 0.6, kCoveredDepth}, {w + 0.2, -0.04}, {w + 1.5, -0.15}};
      covered_until_ = w - 0.6;
      blend_start_ = w + 1.5;
      blend_end_ = w + 12.0;
      break;
  }
  if (path_follows_hills_) return;
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector3d& point : path.points())
    box.extend(point.head<2>());
  const double margin = reach + 2.0 * kGridCell;
  grid_origin_ = box.min() - Eigen::Vector2d::Constant(margin);
  grid_columns_ = static_cast<int>(std::ceil((box.sizes().x() + 2 * margin) / kGridCell)) + 1;
  grid_rows_ = static_cast<int>(std::ceil((box.sizes().y() + 2 * margin) / kGridCell)) + 1;
  grid_heights_.resize(static_cast<std::size_t>(grid_columns_) * grid_rows_);
  for (int row = 0; row < grid_rows_; ++row) {
    for (int column = 0; column < grid_columns_; ++column) {
      const Eigen::Vector2d xy = grid_origin_ + kGridCell * Eigen::Vector2d(column, row);
      Path::Nearest nearest;
      double radius = 2.0 * kGridCell;
      while (!path.nearest(xy, radius, nearest))
        radius *= 4.0;
      grid_heights_[static_cast<std::size_t>(row) * grid_columns_ + column] = nearest.height;
    }
  }
}

double TerrainModel::reference(const Eigen::Vector2d& xy) const {
  if (path_follows_hills_) return hills_.at(xy);
  const Eigen::Vector2d cell = (xy - grid_origin_) / kGridCell;
  const int column = std::clamp(static_cast<int>(std::floor(cell.x())), 0, grid_columns_ - 2);
  const int row = std::clamp(static_cast<int>(std::floor(cell.y())), 0, grid_rows_ - 2);
  const double fx = std::clamp(cell.x() - column, 0.0, 1.0),
               fy = std::clamp(cell.y() - row, 0.0, 1.0);
  auto at = [&](int c, int r) {
    return grid_heights_[static_cast<std::size_t>(r) * grid_columns_ + c];
  };
  return (1 - fy) * ((1 - fx) * at(column, row) + fx * at(column + 1, row)) +
         fy * ((1 - fx) * at(column, row + 1) + fx * at(column + 1, row + 1));
}

double TerrainModel::profile(double distance) const {
  if (distance <= profile_.front().first) return profile_.front().second;
  for (std::size_t i = 1; i < profile_.size(); ++i) {
    if (distance <= profile_[i].first) {
      const auto& [d0, z0] = profile_[i - 1];
      const auto& [d1, z1] = profile_[i];
      return z0 + (z1 - z0) * (distance - d0) / (d1 - d0);
    }
  }
  return profile_.back().second;
}

double TerrainModel::berm_height(const Path::Nearest& nearest) const {
  double height = 0.0;
  for (const Berm& berm : berms_) {
    if (nearest.s < berm.s0 || nearest.s > berm.s1 || nearest.lateral * berm.side <= 0.0) continue;
    // Full height between the ramps, a trapezoid across.
    const double along =
        std::min({1.0, (nearest.s - berm.s0) / berm.ramp, (berm.s1 - nearest.s) / berm.ramp});
    const double across = std::abs(nearest.lateral) - berm.toe;
    const double slope = 1.5 * berm.height;  // horizontal run of each side
    double rise = 0.0;
    if (across > 0.0 && across < slope) {
      rise = across / slope;
    } else if (across >= slope && across <= slope + berm.crest) {
      rise = 1.0;
    } else if (across > slope + berm.crest && across < 2.0 * slope + berm.crest) {
      rise = (2.0 * slope + berm.crest - across) / slope;
    }
    height = std::max(height, berm.height * rise * along);
  }
  return height;
}

double TerrainModel::height(const Eigen::Vector2d& xy, bool* covered) const {
  Path::Nearest nearest;
  bool is_covered = false;
  double result;
  if (!path_.nearest(xy, blend_end_, nearest)) {
    result = far_height(xy);
  } else {
    const double distance = std::abs(nearest.lateral);
    is_covered = distance < covered_until_;
    const double near = nearest.height + profile(distance);
    const double weight = smoothstep(blend_start_, blend_end_, distance);
    result = (1.0 - weight) * near + weight * far_height(xy) + berm_height(nearest);
  }
  // Side streets: the ground is out of sight under them and level with their sidewalks beside
  // them, blending into the rest over a few metres.
  constexpr double kSideBlend = 8.0;
  for (const SideStreet& street : side_streets_) {
    const double outer = street.outer();
    Path::Nearest side;
    if (!street.path->nearest(xy, outer + kSideBlend, side)) continue;
    const bool beside = side.distance <= std::abs(side.lateral) + 1e-6;  // not past its ends
    if (beside && side.distance < outer - 0.3) {
      if (covered) *covered = true;
      return side.height + kCoveredDepth;
    }
    const double level = side.height + street.curb_height;
    const double weight = smoothstep(outer + 1.0, outer + kSideBlend, side.distance);
    result = (1.0 - weight) * level + weight * result;
  }
  if (covered) *covered = is_covered;
  return result;
}

bool TerrainModel::near_road(const Eigen::Vector2d& centre, double radius) const {
  Path::Nearest unused;
  return path_.nearest(centre, blend_end_ + radius, unused);
}

bool on_other_stretch(const Path& path, const Eigen::Vector2d& xy, double s, double half_width) {
  Path::Nearest nearest;
  if (!path.nearest(xy, half_width, nearest)) return false;
  double gap = std::abs(nearest.s - s);
  if (path.closed()) gap = std::min(gap, path.length() - gap);
  return gap > 2.0 * half_width + 5.0;
}

void build_road(World& world, const Path& path, const std::vector<CrossSectionPiece>& section,
                const std::vector<SideStreet>& side_streets, double skip_start_off_carriageway) {
  std::vector<uint32_t> surfaces;
  for (const CrossSectionPiece& piece : section)
    surfaces.push_back(world.add_surface(piece.semantic, 0, piece.reflectivity));
  double carriageway = 0.0;
  for (const CrossSectionPiece& piece : section) {
    if (piece.semantic == SemanticClass::kRoad)
      carriageway = std::max({carriageway, std::abs(piece.d0), std::abs(piece.d1)});
  }
  const int stations = static_cast<int>(path.points().size());
  const int segments = path.closed() ? stations : stations - 1;
  for (int i = 0; i < segments; ++i) {
    const double s0 = i * path.spacing();
    const Path::Frame a = path.at(s0), b = path.at(s0 + path.spacing());
    for (std::size_t k = 0; k < section.size(); ++k) {
      const CrossSectionPiece& piece = section[k];
      if (piece.dash_period > 0.0 && std::fmod(s0, piece.dash_period) >= piece.dash_on) continue;
      auto corner = [&](const Path::Frame& f, double d, double z) -> Eigen::Vector3f {
        Eigen::Vector3d p = f.position + d * f.left;
        p.z() += z;
        return p.cast<float>();
      };
      const Eigen::Vector3f p0 = corner(a, piece.d0, piece.z0), p1 = corner(a, piece.d1, piece.z1),
                            q1 = corner(b, piece.d1, piece.z1), q0 = corner(b, piece.d0, piece.z0);
      const Eigen::Vector3f centre = 0.25f * (p0 + p1 + q0 + q1);
      const bool off_carriageway = piece.semantic != SemanticClass::kRoad;
      if (off_carriageway) {
        const Eigen::Vector2d xy = centre.head<2>().cast<double>();
        if (s0 < skip_start_off_carriageway ||
            on_other_stretch(path, xy, s0 + 0.5 * path.spacing(), carriageway))
          continue;
        bool across_side_street = false;
        for (const SideStreet& street : side_streets) {
          Path::Nearest unused;
          across_side_street |= street.path->nearest(xy, street.half_width + 0.2, unused);
        }
        if (across_side_street) continue;
      }
      world.tile_at(centre).add_quad(p0, p1, q1, q0, surfaces[k]);
    }
  }
}

void build_terrain(World& world, const Path& path, const TerrainModel& terrain, double reach) {
  const float tile = world.tile_size;
  std::map<TileKey, bool> wanted;
  const double margin = reach + tile;
  for (const Eigen::Vector3d& point : path.points()) {
    const int x0 = static_cast<int>(std::floor((point.x() - margin) / tile));
    const int x1 = static_cast<int>(std::floor((point.x() + margin) / tile));
    const int y0 = static_cast<int>(std::floor((point.y() - margin) / tile));
    const int y1 = static_cast<int>(std::floor((point.y() + margin) / tile));
    for (int x = x0; x <= x1; ++x) {
      for (int y = y0; y <= y1; ++y) {
        const Eigen::Vector2d centre((x + 0.5) * tile, (y + 0.5) * tile);
        if ((centre - point.head<2>()).norm() <= margin) wanted[{x, y}] = true;
      }
    }
  }
  const uint32_t surface = world.add_surface(SemanticClass::kTerrain, 0, 0.4f);
  const int n = static_cast<int>(std::lround(tile / kTerrainStep));
  for (const auto& [key, unused] : wanted) {
    GeometrySet& set = world.tiles[key];
    const uint32_t first = static_cast<uint32_t>(set.vertices.size());
    std::vector<char> covered((n + 1) * (n + 1));
    const Eigen::Vector2d centre((key.first + 0.5) * tile, (key.second + 0.5) * tile);
    const bool near_road = terrain.near_road(centre, 0.75 * tile);  // > half the diagonal
    for (int row = 0; row <= n; ++row) {
      for (int column = 0; column <= n; ++column) {
        const Eigen::Vector2d xy(key.first * tile + column * kTerrainStep,
                                 key.second * tile + row * kTerrainStep);
        bool is_covered = false;
        const double z = near_road ? terrain.height(xy, &is_covered) : terrain.far_height(xy);
        covered[row * (n + 1) + column] = is_covered;
        set.add_vertex(Eigen::Vector3f(xy.x(), xy.y(), z));
      }
    }
    auto index = [&](int column, int row) { return row * (n + 1) + column; };
    for (int row = 0; row < n; ++row) {
      for (int column = 0; column < n; ++column) {
        const int a = index(column, row), b = index(column + 1, row),
                  c = index(column + 1, row + 1), d = index(column, row + 1);
        if (covered[a] && covered[b] && covered[c] && covered[d]) continue;
        set.triangles.push_back({first + a, first + b, first + c});
        set.triangles.push_back({first + a, first + c, first + d});
        set.triangle_surfaces.insert(set.triangle_surfaces.end(), 2, surface);
      }
    }
  }
}

}  // namespace adaptive_lego_loam::sim
