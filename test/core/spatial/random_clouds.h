#pragma once
// Random clouds and brute-force answers, for the spatial structures' tests.

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"

namespace adaptive_lego_loam::test {

inline CloudPtr random_cloud(int size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(-10.f, 10.f);
  CloudPtr cloud(new Cloud);
  for (int i = 0; i < size; ++i) {
    CloudPoint p;
    p.x = coordinate(random);
    p.y = coordinate(random);
    p.z = 0.1f * coordinate(random);  // flat, as scans are
    cloud->push_back(p);
  }
  // Duplicates and points on one line: ties and zero extents.
  for (int i = 0; i < 20; ++i)
    cloud->push_back((*cloud)[i]);
  for (int i = 0; i < 30; ++i) {
    CloudPoint p;
    p.x = 0.5f * static_cast<float>(i);
    p.y = p.z = 1.f;
    cloud->push_back(p);
  }
  return cloud;
}

// Squared distances of the k nearest points within the bound, nearest first.
inline std::vector<float> brute_force(const Cloud& cloud, const Eigen::Vector3f& query, int k,
                                      float max_squared) {
  std::vector<float> squared;
  for (const CloudPoint& p : cloud) {
    const float dx = p.x - query.x(), dy = p.y - query.y(), dz = p.z - query.z();
    const float d = dx * dx + dy * dy + dz * dz;  // as the tree sums them
    if (d <= max_squared) squared.push_back(d);
  }
  std::sort(squared.begin(), squared.end());
  squared.resize(std::min<std::size_t>(squared.size(), k));
  return squared;
}

inline std::vector<Eigen::Vector3f> sorted_points(const Cloud& cloud) {
  std::vector<Eigen::Vector3f> points;
  for (const CloudPoint& p : cloud)
    points.push_back(p.getVector3fMap());
  std::sort(points.begin(), points.end(), [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return points;
}

}  // namespace adaptive_lego_loam::test
