#pragma once
// The k best candidates of a nearest-neighbour search (the KD-tree's and the voxel map's), nearest
// first. A candidate must beat `worst` strictly, so ties keep the one found first.

#include <cstdint>

namespace adaptive_lego_loam {

struct NearestCandidates {
  int k = 0, count = 0;
  uint32_t* indices = nullptr;
  float* squared = nullptr;
  float worst = 0.f;  // the bound, then the k-th distance once k were found

  void add(float distance, uint32_t index) {
    int i = count;
    for (; i > 0 && squared[i - 1] > distance; --i) {
      if (i < k) {
        squared[i] = squared[i - 1];
        indices[i] = indices[i - 1];
      }
    }
    if (i < k) {
      squared[i] = distance;
      indices[i] = index;
    }
    if (count < k) ++count;
    if (count == k) worst = squared[k - 1];
  }
};

}  // namespace adaptive_lego_loam
