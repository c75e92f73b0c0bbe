#pragma once
// Boxes and labelled objects for the clustering benchmark's tests.

#include "adaptive_lego_loam/eval/clustering_benchmark.h"

namespace adaptive_lego_loam::test {

inline AxisAlignedBox box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {{x0, y0, z0}, {x1, y1, z1}};
}

inline LabelledObject object(const AxisAlignedBox& b) {
  return {"car", b};
}

}  // namespace adaptive_lego_loam::test
