#include "adaptive_lego_loam/core/common/cloud.h"

namespace adaptive_lego_loam {

CloudPoint to_cloud_point(const ScanPoint& p, float intensity) {
  CloudPoint q;
  q.x = p.x;
  q.y = p.y;
  q.z = p.z;
  q.intensity = intensity;
  return q;
}

CloudPtr transform_cloud(const Cloud& in, const Eigen::Isometry3d& pose) {
  CloudPtr out(new Cloud);
  out->resize(in.size());
  const Eigen::Matrix3f rotation = pose.rotation().cast<float>();
  const Eigen::Vector3f translation = pose.translation().cast<float>();
  for (std::size_t i = 0; i < in.size(); ++i) {
    const CloudPoint& p = in[i];
    CloudPoint& q = (*out)[i];
    q.getVector3fMap() = rotation * p.getVector3fMap() + translation;
    q.intensity = p.intensity;
  }
  return out;
}

}  // namespace adaptive_lego_loam
