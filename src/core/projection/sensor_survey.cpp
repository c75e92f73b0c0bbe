#include "adaptive_lego_loam/core/projection/sensor_survey.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>

namespace adaptive_lego_loam {
namespace {

constexpr double kDeg = 180.0 / M_PI;
constexpr double kMinFitRange = 0.3;      // m: nearer points say little about a beam's slope
constexpr double kClusterGapDeg = 0.03;   // elevations this far apart start another beam
constexpr double kDiscreteBandDeg = 0.5;  // a beam's points lie within this of each other
constexpr int kMinBeamPoints = 30;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[512];
  std::snprintf(text, sizeof(text), pattern, a, b, c);
  return text;
}

bool usable(const ScanPoint& p) {
  return std::isfinite(p.x + p.y + p.z) && (p.x != 0.f || p.y != 0.f || p.z != 0.f);
}
double horizontal(const ScanPoint& p) {
  return std::hypot(p.x, p.y);
}
double azimuth(const ScanPoint& p) {
  return std::atan2(p.y, p.x);
}

double quantile(std::vector<double> values, double share) {
  if (values.empty()) return 0.0;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(share * (values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}
double median(std::vector<double> values) {
  return quantile(std::move(values), 0.5);
}

// The rows of one scan's points: -1 where a point is unusable or belongs to no beam.
using PointRows = std::vector<int>;

// z = offset + slope * r through a beam's points (r horizontal), trimmed once at three times the
// RMS of the angle each point makes with the line.
struct LineFit {
  double slope = 0.0, offset = 0.0, rms_deg = 0.0;
  long points = 0;
};

LineFit fit_line(const std::vector<std::pair<double, double>>& samples) {
  LineFit fit;
  std::vector<char> keep(samples.size(), 1);
  for (int pass = 0; pass < 2; ++pass) {
    double n = 0, sr = 0, sz = 0, srr = 0, srz = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (!keep[i]) continue;
      const auto [r, z] = samples[i];
      n += 1;
      sr += r;
      sz += z;
      srr += r * r;
      srz += r * z;
    }
    const double det = n * srr - sr * sr;
    if (n < 2 || std::abs(det) < 1e-12) return fit;
    fit.slope = (n * srz - sr * sz) / det;
    fit.offset = (sz - fit.slope * sr) / n;
    double squares = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (!keep[i]) continue;
      const double angle =
          (samples[i].second - fit.offset - fit.slope * samples[i].first) / samples[i].first;
      squares += angle * angle;
    }
    fit.points = static_cast<long>(n);
    fit.rms_deg = std::sqrt(squares / n) * kDeg;
    const double limit = 3.0 * fit.rms_deg / kDeg + 1e-9;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const double angle =
          (samples[i].second - fit.offset - fit.slope * samples[i].first) / samples[i].first;
      keep[i] = std::abs(angle) <= limit;
    }
  }
  return fit;
}

// Beams from a label per point (ring, laser or cluster): a line through each label's points.
// `min_points`: fewer make no beam (a ring field names its beams: a few points will do).
std::vector<SurveyedBeam> fit_beams(const std::vector<Scan>& scans,
                                    const std::vector<PointRows>& labels, int min_points) {
  std::map<int, std::vector<std::pair<double, double>>> samples;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (std::size_t i = 0; i < scans[s].points.size(); ++i) {
      const ScanPoint& p = scans[s].points[i];
      if (labels[s][i] < 0 || horizontal(p) < kMinFitRange) continue;
      samples[labels[s][i]].emplace_back(horizontal(p), p.z);
    }
  }
  std::vector<SurveyedBeam> beams;
  for (const auto& [label, points] : samples) {
    if (static_cast<int>(points.size()) < min_points) continue;
    const LineFit fit = fit_line(points);
    beams.push_back({std::atan(fit.slope) * kDeg, fit.offset, fit.rms_deg, fit.points, label});
  }
  std::sort(beams.begin(), beams.end(), [](const SurveyedBeam& a, const SurveyedBeam& b) {
    return a.elevation_deg < b.elevation_deg;
  });
  return beams;
}

std::vector<PointRows> ring_labels(const std::vector<Scan>& scans) {
  std::vector<PointRows> labels;
  for (const Scan& scan : scans) {
    PointRows rows(scan.points.size(), -1);
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
      if (usable(scan.points[i])) rows[i] = scan.points[i].ring;
    }
    labels.push_back(std::move(rows));
  }
  return labels;
}

// The laser of each point when a scan holds one laser's sweep after the other, as KITTI's files
// do: the whole turns its azimuth has made along the file. Empty when the file is not so ordered
// (fewer than 4 turns, a laser of few points).
PointRows lasers_in_file_order(const Scan& scan) {
  PointRows lasers(scan.points.size(), -1);
  double turned = 0.0, last = 0.0;
  bool started = false;
  int count = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const ScanPoint& p = scan.points[i];
    if (!usable(p)) continue;
    const double a = azimuth(p);
    if (started) turned += std::remainder(a - last, 2.0 * M_PI);
    started = true;
    last = a;
    lasers[i] = static_cast<int>(std::floor(std::abs(turned) / (2.0 * M_PI) + 1e-3));
    count = std::max(count, lasers[i] + 1);
  }
  if (count < 4 || count > 512) return {};
  std::vector<int> per_laser(count, 0);
  for (int laser : lasers)
    if (laser >= 0) ++per_laser[laser];
  if (*std::min_element(per_laser.begin(), per_laser.end()) < 50) return {};
  return lasers;
}

std::vector<PointRows> file_order_labels(const std::vector<Scan>& scans) {
  std::vector<PointRows> labels;
  std::optional<int> lasers;
  for (const Scan& scan : scans) {
    PointRows rows = lasers_in_file_order(scan);
    if (rows.empty()) return {};
    const int count = *std::max_element(rows.begin(), rows.end()) + 1;
    if (lasers && *lasers != count) return {};
    lasers = count;
    labels.push_back(std::move(rows));
  }
  return labels;
}

// Clusters of the points' elevations (seen from the sensor origin): a beam
// where they pack together, split where kClusterGapDeg lies between neighbours. `problem` says
// when most points lie in no narrow band: no discrete beams.
std::vector<PointRows> elevation_labels(const std::vector<Scan>& scans, std::string& problem) {
  std::vector<std::pair<float, std::pair<int, int>>> elevations;  // elevation, scan, point
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (std::size_t i = 0; i < scans[s].points.size(); ++i) {
      const ScanPoint& p = scans[s].points[i];
      if (!usable(p) || horizontal(p) < kMinFitRange) continue;
      elevations.push_back({static_cast<float>(std::atan2(p.z, horizontal(p)) * kDeg),
                            {static_cast<int>(s), static_cast<int>(i)}});
    }
  }
  std::sort(elevations.begin(), elevations.end());
  std::vector<PointRows> labels;
  for (const Scan& scan : scans)
    labels.emplace_back(scan.points.size(), -1);
  std::size_t first = 0;
  int cluster = 0;
  long wide = 0;
  for (std::size_t i = 1; i <= elevations.size(); ++i) {
    if (i < elevations.size() && elevations[i].first - elevations[i - 1].first <= kClusterGapDeg)
      continue;
    const std::size_t size = i - first;
    // The middle 90 % of the cluster's elevations: a beam's are within a fraction of a degree.
    const double band = elevations[first + size * 95 / 100 - (size >= 20 ? 1 : 0)].first -
                        elevations[first + size * 5 / 100].first;
    if (band > kDiscreteBandDeg) wide += static_cast<long>(size);
    if (static_cast<int>(size) >= kMinBeamPoints) {
      for (std::size_t k = first; k < i; ++k)
        labels[elevations[k].second.first][elevations[k].second.second] = cluster;
      ++cluster;
    }
    first = i;
  }
  if (!elevations.empty() && 10 * wide > 3 * static_cast<long>(elevations.size())) {
    problem = format(
        "the elevations form no discrete beams (%.0f %% of the points lie in bands wider than "
        "%.1f deg): a rosette or solid-state pattern, several sensors merged into one cloud, or "
        "beams whose origins lie off the sensor's (an HDL-64E's) without a ring field to tell "
        "them apart",
        100.0 * wide / elevations.size(), kDiscreteBandDeg);
  }
  return labels;
}

// Rings that sent no point but lie among (or below the first of) the ring numbers seen, when the
// rings seen are evenly spaced in elevation: their beams continue the spacing (a top-down
// numbered sensor's upper beams see nothing on an open road). Returns the rings added.
std::string add_silent_even_rings(std::vector<SurveyedBeam>& beams) {
  std::vector<SurveyedBeam> by_ring = beams;
  std::sort(by_ring.begin(), by_ring.end(),
            [](const SurveyedBeam& a, const SurveyedBeam& b) { return a.ring < b.ring; });
  if (by_ring.size() < 3) return "";
  const SurveyedBeam &first = by_ring.front(), &last = by_ring.back();
  const double per_ring = (last.elevation_deg - first.elevation_deg) / (last.ring - first.ring);
  for (const SurveyedBeam& beam : by_ring) {
    const double expected = first.elevation_deg + per_ring * (beam.ring - first.ring);
    if (std::abs(beam.elevation_deg - expected) > 2e-3) return "";
  }
  std::vector<bool> seen(last.ring + 1, false);
  for (const SurveyedBeam& beam : by_ring)
    seen[beam.ring] = true;
  std::string added;
  for (int ring = 0; ring <= last.ring; ++ring) {
    if (seen[ring]) continue;
    SurveyedBeam beam;
    beam.ring = ring;
    beam.elevation_deg = first.elevation_deg + per_ring * (ring - first.ring);
    beams.push_back(beam);
    added += " " + std::to_string(ring);
  }
  std::sort(beams.begin(), beams.end(), [](const SurveyedBeam& a, const SurveyedBeam& b) {
    return a.elevation_deg < b.elevation_deg;
  });
  return added;
}

// Relabels points from their label (ring, laser, cluster) to the row of its beam, and drops the
// points that lie off it (a laser's first points that the file order gave the laser before).
void labels_to_rows(const std::vector<Scan>& scans, const std::vector<SurveyedBeam>& beams,
                    std::vector<PointRows>& labels) {
  std::map<int, int> row_of;
  for (std::size_t row = 0; row < beams.size(); ++row)
    row_of[beams[row].ring] = static_cast<int>(row);
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (std::size_t i = 0; i < labels[s].size(); ++i) {
      const auto it = row_of.find(labels[s][i]);
      labels[s][i] = it == row_of.end() ? -1 : it->second;
      if (labels[s][i] < 0) continue;
      const SurveyedBeam& beam = beams[labels[s][i]];
      const ScanPoint& p = scans[s].points[i];
      const double r = std::max(horizontal(p), 1e-3);
      const double off = std::atan2(p.z - beam.offset_m, r) * kDeg - beam.elevation_deg;
      if (std::abs(off) > std::max(3.0 * beam.spread_deg, 0.05)) labels[s][i] = -1;
    }
  }
}

double azimuth_coverage(const std::vector<Scan>& scans) {
  std::vector<char> bins(360, 0);
  for (const Scan& scan : scans) {
    for (const ScanPoint& p : scan.points) {
      if (!usable(p) || horizontal(p) < 0.5) continue;
      const int bin = static_cast<int>(std::floor((azimuth(p) * kDeg + 180.0))) % 360;
      bins[std::clamp(bin, 0, 359)] = 1;
    }
  }
  return std::accumulate(bins.begin(), bins.end(), 0) / 360.0;
}

// Each row's point indices in the order they were fired: by time when the points carry it,
// else as the file holds them.
std::vector<std::vector<int>> row_points(const Scan& scan, const PointRows& rows, int row_count) {
  std::vector<std::vector<int>> out(row_count);
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i] >= 0) out[rows[i]].push_back(static_cast<int>(i));
  if (scan.has_time) {
    for (auto& indices : out) {
      std::stable_sort(indices.begin(), indices.end(),
                       [&](int a, int b) { return scan.points[a].time < scan.points[b].time; });
    }
  }
  return out;
}

// The azimuth step between neighbouring points of a beam (rad): the median step, then the mean
// of the steps within 10 % of it.
double azimuth_step(const std::vector<Scan>& scans, const std::vector<PointRows>& rows,
                    int row_count) {
  std::vector<double> steps;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (const auto& indices : row_points(scans[s], rows[s], row_count)) {
      std::vector<double> azimuths;
      for (int i : indices)
        azimuths.push_back(azimuth(scans[s].points[i]));
      std::sort(azimuths.begin(), azimuths.end());
      for (std::size_t k = 1; k < azimuths.size(); ++k) {
        if (azimuths[k] - azimuths[k - 1] > 1e-7) steps.push_back(azimuths[k] - azimuths[k - 1]);
      }
    }
  }
  const double rough = median(steps);
  double sum = 0;
  long n = 0;
  for (double step : steps) {
    if (std::abs(step - rough) <= 0.1 * rough) {
      sum += step;
      ++n;
    }
  }
  return n > 0 ? sum / n : rough;
}

// Where a raw sweep shows its motion: the sweep's first and last columns are neighbours in
// azimuth, a scan period apart in time. The share of such neighbours whose ranges jump (more
// than 0.3 m and 2 %), at the seam and elsewhere in the row.
// Points of the ground (below `ground_z`) are left out: they lie where they did however the
// sensor moved along it.
void seam_jumps(const Scan& scan, const std::vector<std::vector<int>>& rows, double step,
                double ground_z, long& seam_pairs, long& seam_jumps_out, long& pairs, long& jumps) {
  const auto range = [&](int i) {
    const ScanPoint& p = scan.points[i];
    return std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
  };
  const auto jump = [&](int a, int b) {
    const double ra = range(a), rb = range(b);
    return std::abs(ra - rb) > std::max(0.3, 0.005 * std::min(ra, rb));
  };
  const auto near_in_azimuth = [&](int a, int b) {
    return std::abs(std::remainder(azimuth(scan.points[a]) - azimuth(scan.points[b]),
                                   2.0 * M_PI)) <= 3.0 * step;
  };
  for (const auto& all : rows) {
    std::vector<int> indices;
    for (int i : all)
      if (scan.points[i].z > ground_z) indices.push_back(i);
    const int n = static_cast<int>(indices.size());
    if (n < 100) continue;
    const int k = 1;
    for (int a = 0; a < k; ++a) {
      for (int b = n - k; b < n; ++b) {
        if (!near_in_azimuth(indices[a], indices[b])) continue;
        ++seam_pairs;
        seam_jumps_out += jump(indices[a], indices[b]);
        break;
      }
    }
    for (int i = n / 4; i < 3 * n / 4; ++i) {
      if (!near_in_azimuth(indices[i], indices[i + 1])) continue;
      ++pairs;
      jumps += jump(indices[i], indices[i + 1]);
    }
  }
}

// The change of range between the first two scans, cell by cell (row, azimuth step), that a
// fifth of the cells exceed: about how far the sensor moved (most cells, the road and the walls
// along it, change little).
double scan_to_scan_change(const std::vector<Scan>& scans, const std::vector<PointRows>& rows,
                           double step) {
  if (scans.size() < 2) return 0.0;
  const auto cells = [&](std::size_t s) {
    std::map<std::pair<int, int>, double> image;
    for (std::size_t i = 0; i < scans[s].points.size(); ++i) {
      if (rows[s][i] < 0) continue;
      const ScanPoint& p = scans[s].points[i];
      const int column = static_cast<int>(std::floor((azimuth(p) + M_PI) / step));
      image[{rows[s][i], column}] = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    }
    return image;
  };
  const auto first = cells(0), second = cells(1);
  std::vector<double> changes;
  for (const auto& [cell, range] : first) {
    const auto it = second.find(cell);
    if (it != second.end()) changes.push_back(std::abs(it->second - range));
  }
  return quantile(changes, 0.8);
}

// A plane through the points below the sensor (RANSAC with a fixed seed, then least squares on
// its inliers), within 25 deg of level: the sensor's height above it and its tilt.
void fit_ground(const Scan& scan, SensorSurvey& survey) {
  std::vector<std::array<double, 3>> below;
  for (const ScanPoint& p : scan.points) {
    const double r = horizontal(p);
    if (usable(p) && p.z < -0.3 && r >= 3.0 && r <= 40.0) below.push_back({p.x, p.y, p.z});
  }
  if (below.size() < 100) return;
  std::mt19937 rng(1);
  std::uniform_int_distribution<std::size_t> pick(0, below.size() - 1);
  const auto inliers_of = [&](const std::array<double, 4>& plane) {
    std::vector<std::size_t> inliers;
    for (std::size_t i = 0; i < below.size(); ++i) {
      const auto& q = below[i];
      if (std::abs(plane[0] * q[0] + plane[1] * q[1] + plane[2] * q[2] + plane[3]) < 0.1)
        inliers.push_back(i);
    }
    return inliers;
  };
  std::vector<std::size_t> best;
  for (int iteration = 0; iteration < 300; ++iteration) {
    const auto &a = below[pick(rng)], &b = below[pick(rng)], &c = below[pick(rng)];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (norm < 1e-9) continue;
    for (double& x : n)
      x /= (n[2] < 0 ? -norm : norm);
    if (n[2] < std::cos(25.0 / kDeg)) continue;
    const std::vector<std::size_t> inliers =
        inliers_of({n[0], n[1], n[2], -(n[0] * a[0] + n[1] * a[1] + n[2] * a[2])});
    if (inliers.size() > best.size()) best = inliers;
  }
  if (best.size() < below.size() / 10) return;
  // z = gx x + gy y + h through the inliers: the normal equations, by Cramer's rule.
  double m[3][3] = {}, t[3] = {};
  for (std::size_t i : best) {
    const double row[3] = {below[i][0], below[i][1], 1.0};
    for (int j = 0; j < 3; ++j) {
      t[j] += row[j] * below[i][2];
      for (int k = 0; k < 3; ++k)
        m[j][k] += row[j] * row[k];
    }
  }
  const auto det = [](const double(&a)[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det(m);
  if (std::abs(d) < 1e-12) return;
  double solution[3];
  for (int j = 0; j < 3; ++j) {
    double replaced[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        replaced[r][k] = k == j ? t[r] : m[r][k];
    solution[j] = det(replaced) / d;
  }
  const double slope = std::hypot(solution[0], solution[1]);
  survey.ground_tilt_deg = std::atan(slope) * kDeg;
  survey.sensor_height_m = std::abs(solution[2]) / std::sqrt(slope * slope + 1.0);
}

void describe(SensorSurvey& survey) {
  std::vector<std::string>& out = survey.report;
  const auto& beams = survey.beams;
  std::string rows = std::to_string(beams.size()) + " rows from " + survey.rows_from;
  if (!survey.ring_to_row.empty()) rows += " (ring_to_row puts them bottom-up)";
  out.push_back(rows);
  double min_gap = INFINITY, max_gap = 0.0, max_spread = 0.0;
  for (std::size_t row = 1; row < beams.size(); ++row) {
    const double gap = beams[row].elevation_deg - beams[row - 1].elevation_deg;
    min_gap = std::min(min_gap, gap);
    max_gap = std::max(max_gap, gap);
  }
  for (const SurveyedBeam& beam : beams)
    max_spread = std::max(max_spread, beam.spread_deg);
  out.push_back(format("beams from %.3f to %.3f deg, ", beams.front().elevation_deg,
                       beams.back().elevation_deg) +
                format("%.3f to %.3f deg apart; ", min_gap, max_gap) +
                format("their points within %.3f deg (RMS) of them", max_spread));
  double max_offset = 0.0;
  for (const SurveyedBeam& beam : beams)
    max_offset = std::max(max_offset, std::abs(beam.offset_m));
  out.push_back(format("beam origins up to %.3f m above or below the sensor's at a median range "
                       "of %.1f m: ",
                       max_offset, survey.typical_range_m) +
                (survey.offsets_matter ? "beam_offsets_m (they move a point by over a tenth of "
                                         "a row spacing)"
                                       : "left out (they move a point by under a tenth of a "
                                         "row spacing)"));
  out.push_back(format("%.0f firings a turn (azimuth step %.4f deg)", survey.firings,
                       survey.azimuth_step_deg) +
                (survey.columns > survey.firings
                     ? format("; %.0f columns: a row holds up to 3 %% fewer points", survey.columns)
                     : std::string("")));
  out.push_back(format("ranges seen from %.2f to %.1f m", survey.min_range_m, survey.max_range_m));
  if (survey.sensor_height_m) {
    out.push_back(format("ground: a plane %.2f m below the sensor, tilted %.2f deg",
                         *survey.sensor_height_m, *survey.ground_tilt_deg) +
                  format("; ground rows 0..%.0f (beams at or below -1 deg)", survey.ground_rows));
  } else {
    out.push_back(
        format("ground: no plane below the sensor found; ground rows 0..%.0f (beams at "
               "or below -1 deg)",
               survey.ground_rows));
  }
  out.push_back(survey.has_time
                    ? format("the points carry times, %.1f ms a sweep; ", 1e3 * survey.time_span_s)
                    : std::string("the points carry no time; "));
  out.back() +=
      format("scan period %.4f s ", survey.scan_period_s) + "(" + survey.period_from + ")";
  std::string deskew =
      format(
          "the sweep's ends: %.0f %% of %.0f neighbours off the ground jump in range across "
          "the seam, ",
          100.0 * survey.seam_jump_share, survey.seam_pairs) +
      format("%.0f %% elsewhere; %.2f m of change from one scan to the next: ",
             100.0 * survey.neighbour_jump_share, survey.scan_to_scan_change_m);
  if (survey.has_time) {
    deskew += "the points carry their times in the sweep, a raw sweep (deskewed: false)";
  } else if (!survey.deskewed) {
    deskew += "cannot tell whether de-skewed (deskewed: false; true if the recording is)";
  } else {
    deskew +=
        *survey.deskewed ? "looks de-skewed (deskewed: true)" : "raw, skewed (deskewed: false)";
  }
  out.push_back(deskew);
}

}  // namespace

SensorSurvey survey_sensor(const std::vector<Scan>& scans) {
  SensorSurvey survey;
  survey.scans = static_cast<int>(scans.size());
  long usable_points = 0;
  for (const Scan& scan : scans)
    usable_points += std::count_if(scan.points.begin(), scan.points.end(), usable);
  if (usable_points == 0) throw std::invalid_argument("the scans hold no finite point");
  survey.azimuth_coverage = azimuth_coverage(scans);
  if (survey.azimuth_coverage < 0.75) {
    survey.not_spinning = format(
        "the points cover %.0f deg of azimuth, not a turn: a solid-state or forward-looking "
        "field of view",
        360.0 * survey.azimuth_coverage);
    return survey;
  }
  survey.ring_field =
      std::all_of(scans.begin(), scans.end(), [](const Scan& scan) { return scan.has_ring; });
  std::vector<PointRows> labels;
  if (survey.ring_field) {
    labels = ring_labels(scans);
    survey.rows_from = "the ring field";
  } else if (!(labels = file_order_labels(scans)).empty()) {
    survey.rows_from = "the order of the points (one laser's sweep after the other)";
  } else {
    labels = elevation_labels(scans, survey.not_spinning);
    survey.rows_from = "the elevations";
    if (!survey.not_spinning.empty()) return survey;
  }
  survey.beams = fit_beams(scans, labels, survey.ring_field ? 5 : kMinBeamPoints);
  if (survey.beams.size() < 2) {
    survey.not_spinning = "fewer than two beams found";
    return survey;
  }
  int merged = 0;
  const SurveyedBeam* worst = &survey.beams.front();
  for (const SurveyedBeam& beam : survey.beams) {
    merged += beam.spread_deg > kDiscreteBandDeg;
    if (beam.spread_deg > worst->spread_deg) worst = &beam;
  }
  if (4 * merged > static_cast<int>(survey.beams.size())) {
    survey.not_spinning =
        format("the points of %.0f of %.0f rings lie on no one cone (ring %.0f: ", merged,
               survey.beams.size(), worst->ring) +
        format(
            "%.2f deg RMS about it): several sensors merged into one cloud, or a ring field "
            "that is not the laser's",
            worst->spread_deg);
    return survey;
  }
  if (survey.ring_field) {
    const std::string added = add_silent_even_rings(survey.beams);
    if (!added.empty()) {
      survey.report.push_back("no point came with ring" + added +
                              ": evenly spaced like the others, their beams continue the "
                              "spacing");
    }
  }
  labels_to_rows(scans, survey.beams, labels);
  const int rows = static_cast<int>(survey.beams.size());
  if (survey.ring_field) {
    bool bottom_up = true;
    int max_ring = 0;
    for (int row = 0; row < rows; ++row) {
      bottom_up &= survey.beams[row].ring == row;
      max_ring = std::max(max_ring, survey.beams[row].ring);
    }
    if (!bottom_up) {
      survey.ring_to_row.assign(max_ring + 1, -1);
      for (int row = 0; row < rows; ++row)
        survey.ring_to_row[survey.beams[row].ring] = row;
      std::string missing;
      for (int ring = 0; ring <= max_ring; ++ring)
        if (survey.ring_to_row[ring] < 0) missing += " " + std::to_string(ring);
      if (!missing.empty()) {
        survey.report.push_back("no point came with ring" + missing +
                                ": those beams are left out (ring_to_row -1); read more scans, "
                                "or add their rows by hand from the datasheet");
      }
    }
  }
  std::vector<double> ranges, horizontals;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (std::size_t i = 0; i < scans[s].points.size(); ++i) {
      const ScanPoint& p = scans[s].points[i];
      if (!usable(p)) continue;
      ranges.push_back(std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z));
      if (labels[s][i] >= 0) horizontals.push_back(horizontal(p));
    }
  }
  survey.min_range_m = *std::min_element(ranges.begin(), ranges.end());
  survey.max_range_m = *std::max_element(ranges.begin(), ranges.end());
  survey.typical_range_m = median(horizontals);
  double min_gap = INFINITY, max_offset = 0.0;
  for (int row = 1; row < rows; ++row) {
    min_gap =
        std::min(min_gap, survey.beams[row].elevation_deg - survey.beams[row - 1].elevation_deg);
  }
  for (const SurveyedBeam& beam : survey.beams)
    max_offset = std::max(max_offset, std::abs(beam.offset_m));
  survey.offsets_matter =
      std::atan(max_offset / std::max(survey.typical_range_m, 1.0)) * kDeg > 0.1 * min_gap;

  const double step = azimuth_step(scans, labels, rows);
  survey.azimuth_step_deg = step * kDeg;
  survey.firings = step > 0 ? static_cast<int>(std::lround(2.0 * M_PI / step)) : 0;
  survey.columns = survey.firings;
  // A row that holds more points than firings (de-skewed scans, two returns) needs room: 3 % more
  // than the fullest row, in tens.
  for (std::size_t s = 0; s < scans.size(); ++s) {
    std::vector<int> per_row(rows, 0);
    for (int row : labels[s])
      if (row >= 0) ++per_row[row];
    const int fullest = *std::max_element(per_row.begin(), per_row.end());
    if (fullest > survey.firings) {
      survey.columns =
          std::max(survey.columns, static_cast<int>(std::ceil(fullest * 1.03 / 10)) * 10);
    }
  }

  survey.has_time =
      std::all_of(scans.begin(), scans.end(), [](const Scan& scan) { return scan.has_time; });
  std::vector<double> spans, stamp_steps;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    float earliest = INFINITY, latest = -INFINITY;
    for (const ScanPoint& p : scans[s].points) {
      if (!usable(p) || !std::isfinite(p.time)) continue;
      earliest = std::min(earliest, p.time);
      latest = std::max(latest, p.time);
    }
    if (latest > earliest) spans.push_back(latest - earliest);
    if (s > 0 && scans[s].stamp > scans[s - 1].stamp)
      stamp_steps.push_back(scans[s].stamp - scans[s - 1].stamp);
  }
  survey.time_span_s = survey.has_time ? median(spans) : 0.0;
  survey.has_time &= survey.time_span_s > 0.0;
  survey.stamp_step_s = median(stamp_steps);
  // A sweep's times run over all but its last column's share of the period; a span outside 2-40
  // Hz is no whole sweep's.
  double from_times = survey.has_time && survey.columns > 1
                          ? survey.time_span_s * survey.firings / (survey.firings - 1.0)
                          : 0.0;
  if (from_times < 0.025 || from_times > 0.5) from_times = 0.0;
  if (survey.stamp_step_s > 0.0) {
    survey.scan_period_s = std::round(survey.stamp_step_s * 1e4) / 1e4;
    survey.period_from = "the scans' stamps";
    if (from_times > 0.0 && std::abs(from_times - survey.stamp_step_s) > 0.1 * from_times) {
      survey.period_from += format(", though the points' times span %.1f ms", 1e3 * from_times);
    }
  } else if (from_times > 0.0) {
    survey.scan_period_s = std::round(from_times * 1e4) / 1e4;
    survey.period_from = "the points' times";
  } else {
    survey.period_from = "assumed: one scan, and no point times spanning a sweep";
  }

  fit_ground(scans.front(), survey);
  const double ground_z = survey.sensor_height_m ? -*survey.sensor_height_m + 0.3 : -INFINITY;
  long seam_pairs = 0, seam_jumps_count = 0, pairs = 0, jumps = 0;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    seam_jumps(scans[s], row_points(scans[s], labels[s], rows), step, ground_z, seam_pairs,
               seam_jumps_count, pairs, jumps);
  }
  survey.seam_pairs = seam_pairs;
  survey.seam_jump_share =
      seam_pairs > 0 ? static_cast<double>(seam_jumps_count) / seam_pairs : 0.0;
  survey.neighbour_jump_share = pairs > 0 ? static_cast<double>(jumps) / pairs : 0.0;
  survey.scan_to_scan_change_m = scan_to_scan_change(scans, labels, step);
  // A sweep's ends are apart by what the sensor moves in a sweep: beyond the 0.3 m a jump needs,
  // a raw sweep's seam jumps more than its other neighbours; a sweep whose seam does not, though
  // the sensor moved twice that, was de-skewed.
  if (seam_pairs >= 20 && survey.scan_to_scan_change_m > 0.3 &&
      survey.seam_jump_share > 2.0 * survey.neighbour_jump_share + 0.1) {
    survey.deskewed = false;
  } else if (seam_pairs >= 20 && survey.scan_to_scan_change_m > 0.5 &&
             survey.seam_jump_share < survey.neighbour_jump_share + 0.05) {
    survey.deskewed = true;
  }

  if (survey.has_time) survey.deskewed = false;  // drivers that de-skew drop the times
  for (int row = 0; row < rows; ++row)
    if (survey.beams[row].elevation_deg <= -1.0 + 1e-6) survey.ground_rows = row;
  describe(survey);
  return survey;
}

SensorParams surveyed_sensor(const SensorSurvey& survey, const std::string& name) {
  SensorParams sensor;
  sensor.name = name;
  sensor.rows = static_cast<int>(survey.beams.size());
  sensor.columns = survey.columns;
  sensor.row_source = RowSource::kAuto;
  for (const SurveyedBeam& beam : survey.beams) {
    sensor.beam_angles_deg.push_back(beam.elevation_deg);
    if (survey.offsets_matter) sensor.beam_offsets_m.push_back(beam.offset_m);
  }
  sensor.ring_to_row = survey.ring_to_row;
  // The nearest return seen, but no more than 0.5 m: a drive may pass closer than these scans.
  sensor.min_range = std::clamp(std::floor(survey.min_range_m * 10.0) / 10.0, 0.1, 0.5);
  // The farthest return in tens of metres, less 1 % of range noise beyond the sensor's reach.
  sensor.max_range = std::min(1000.0, std::ceil(0.99 * survey.max_range_m / 10.0) * 10.0);
  sensor.mount_angle_deg = 0.0;
  sensor.ground_rows = survey.ground_rows;
  sensor.scan_period = survey.scan_period_s;
  sensor.deskewed = survey.deskewed.value_or(false);
  return sensor;
}

}  // namespace adaptive_lego_loam
