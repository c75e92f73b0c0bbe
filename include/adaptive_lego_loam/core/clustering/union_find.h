#pragma once
// Disjoint sets as parent links over indices (parent[i] == i for a root), for the clusterings
// that find connected groups in one pass. Uniting keeps the smaller index as the root, so a set's
// root is its first element and labelling in index order numbers sets by their first element.

#include <cstdint>
#include <vector>

namespace adaptive_lego_loam {

inline int32_t union_find_root(std::vector<int32_t>& parent, int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}

inline void union_find_unite(std::vector<int32_t>& parent, int32_t a, int32_t b) {
  a = union_find_root(parent, a);
  b = union_find_root(parent, b);
  if (a < b) {
    parent[b] = a;
  } else if (b < a) {
    parent[a] = b;
  }
}

}  // namespace adaptive_lego_loam
