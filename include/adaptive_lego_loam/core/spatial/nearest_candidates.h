#pragma once
// The k best candidates of a nearest-neighbour search (the KD-tree's and the voxel map's), nearest
// first, each with what the search reports for it (an index, a point). A candidate must beat
// `worst` strictly, so ties keep the one found first.

namespace adaptive_lego_loam {

template <class Payload>
struct NearestCandidates {
  int k = 0, count = 0;
  Payload* payloads = nullptr;
  float* squared = nullptr;
  float worst = 0.f;  // the bound, then the k-th distance once k were found

  void add(float distance, const Payload& payload) {
    int i = count;
    for (; i > 0 && squared[i - 1] > distance; --i) {
      if (i < k) {
        squared[i] = squared[i - 1];
        payloads[i] = payloads[i - 1];
      }
    }
    if (i < k) {
      squared[i] = distance;
      payloads[i] = payload;
    }
    if (count < k) ++count;
    if (count == k) worst = squared[k - 1];
  }
};

}  // namespace adaptive_lego_loam
