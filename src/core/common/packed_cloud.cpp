#include "adaptive_lego_loam/core/common/packed_cloud.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {
namespace {

constexpr float kLargest = 32767.f;
constexpr float kIntensityStep = 1.f / 256.f;
constexpr float kMinStep = 1e-4f;  // m: a cloud of a point or two still gets a usable grid

int16_t quantize(float value, float inverse_step) {
  return static_cast<int16_t>(std::clamp(std::lround(value * inverse_step), -32767l, 32767l));
}

}  // namespace

PackedCloud::PackedCloud(const Cloud& cloud) {
  float extent = 0.f;
  for (const CloudPoint& p : cloud) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    extent = std::max({extent, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  }
  step_ = std::max(kMinStep, extent / kLargest);
  const float inverse_step = 1.f / step_;
  points_.reserve(cloud.size());
  for (const CloudPoint& p : cloud) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    points_.push_back(
        {quantize(p.x, inverse_step), quantize(p.y, inverse_step), quantize(p.z, inverse_step),
         quantize(std::isfinite(p.intensity) ? p.intensity : 0.f, 1.f / kIntensityStep)});
  }
}

void PackedCloud::unpack(const Eigen::Isometry3d& pose, Cloud& out) const {
  // The grid step folded into the rotation: one matrix product a point.
  const Eigen::Matrix3f rotation = pose.rotation().cast<float>() * step_;
  const Eigen::Vector3f translation = pose.translation().cast<float>();
  const std::size_t first = out.size();
  out.resize(first + points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Point& p = points_[i];
    CloudPoint& q = out[first + i];
    q.getVector3fMap() = rotation * Eigen::Vector3f(p.x, p.y, p.z) + translation;
    q.intensity = p.intensity * kIntensityStep;
  }
}

CloudPtr PackedCloud::unpack(const Eigen::Isometry3d& pose) const {
  CloudPtr out(new Cloud);
  unpack(pose, *out);
  return out;
}

}  // namespace adaptive_lego_loam
