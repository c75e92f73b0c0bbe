#pragma once
// A drive entered in motion (a bag that starts, or a node restarted, at speed): the first pair of
// scans has no motion to start from. Registered from zero, it settles on the nearest fit, which
// beside a repeating structure (guard-rail posts every 2 m) is an alias of the truth. The pair is
// registered from guesses along x instead (ScanToScanOdometry::align_each), and the result that
// lays most of the scan's non-ground surface onto the previous scan's wins: the posts fit every
// alias alike, so what does not repeat decides.

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/core/spatial/kdtree.h"

namespace adaptive_lego_loam {

// Motions along the sensor's x axis: 0, step, 2 step, ... up to the distance covered in one scan
// period at start_search_max_speed.
std::vector<Eigen::Isometry3d> start_guesses(const OdometryParams& params, double scan_period);

// The points of a scan that the overlap counts: those off the ground (the ground fits every
// motion along the road, and its rings, fixed to the sensor, fit standing still best).
CloudPtr start_points(const std::vector<ScanPoint>& points, const std::vector<uint8_t>& ground_flag,
                      const std::vector<ScanPoint>& outliers);

// How much of the scene `points` (in their sensor's frame) cover lies, moved by `motion` into
// the previous scan's frame, within `radius` of a point of that scan (`previous`): each point
// weighs its squared range, the patch of surface a beam covers growing with it. Counted alone,
// the thousands of points of a car beside the sensor that keeps pace with it (a relative motion
// that is also an alias) outvote the trees and signs further off that do not repeat.
double overlap_area(const PointKdTree& previous, const Cloud& points,
                    const Eigen::Isometry3d& motion, float radius);

}  // namespace adaptive_lego_loam
