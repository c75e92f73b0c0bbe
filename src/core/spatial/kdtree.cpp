#include "adaptive_lego_loam/core/spatial/kdtree.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "adaptive_lego_loam/core/spatial/nearest_candidates.h"

namespace adaptive_lego_loam {
namespace {

constexpr uint32_t kLeafSize = 16;

struct Entry {
  float position[3];
  uint32_t index;  // in the cloud
};

// Internal nodes split on `axis`: the left child (the next node) holds coordinates up to
// `left_max`, the right child (`right`) from `right_min` on. Leaves (axis 3) hold entries
// [begin, end).
struct Node {
  float left_max, right_min;
  uint32_t right_or_begin, end;
  uint32_t axis;
};
constexpr uint32_t kLeaf = 3;

}  // namespace

struct PointKdTree::Index {
  std::vector<Entry> entries;
  std::vector<Node> nodes;

  // Rebuilt in the buffers of the tree before: a tree rebuilt every scan allocates nothing.
  void assign(const Cloud& cloud) {
    nodes.clear();
    entries.resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      entries[i] = {{cloud[i].x, cloud[i].y, cloud[i].z}, static_cast<uint32_t>(i)};
    }
    nodes.reserve(2 * (entries.size() / kLeafSize + 1));
    build(0, static_cast<uint32_t>(entries.size()));
  }

  // Splits at the middle of the axis of largest extent (one partition pass; a median split
  // through nth_element took most of the build).
  uint32_t build(uint32_t begin, uint32_t end) {
    const uint32_t node = static_cast<uint32_t>(nodes.size());
    nodes.push_back({0.f, 0.f, begin, end, kLeaf});
    if (end - begin <= kLeafSize) return node;
    float low[3], high[3];
    for (int a = 0; a < 3; ++a)
      low[a] = high[a] = entries[begin].position[a];
    for (uint32_t i = begin + 1; i < end; ++i) {
      for (int a = 0; a < 3; ++a) {
        low[a] = std::min(low[a], entries[i].position[a]);
        high[a] = std::max(high[a], entries[i].position[a]);
      }
    }
    uint32_t axis = 0;
    for (uint32_t a = 1; a < 3; ++a) {
      if (high[a] - low[a] > high[axis] - low[axis]) axis = a;
    }
    const float split = 0.5f * (low[axis] + high[axis]);
    // Both sides get a point (the lowest and the highest) unless all points coincide.
    if (!(low[axis] < split && split < high[axis])) return node;
    const auto middle_entry =
        std::partition(entries.begin() + begin, entries.begin() + end,
                       [axis, split](const Entry& e) { return e.position[axis] < split; });
    const uint32_t middle = static_cast<uint32_t>(middle_entry - entries.begin());
    float left_max = low[axis], right_min = high[axis];
    for (uint32_t i = begin; i < middle; ++i)
      left_max = std::max(left_max, entries[i].position[axis]);
    for (uint32_t i = middle; i < end; ++i)
      right_min = std::min(right_min, entries[i].position[axis]);
    build(begin, middle);
    const uint32_t right = build(middle, end);
    nodes[node] = {left_max, right_min, right, 0, axis};
    return node;
  }

  // An incremental cell distance (the idea of nanoflann's search): `offsets` holds, per axis, the
  // squared distance from the query to the current cell along it; their sum `cell_distance`
  // bounds every point of the cell from below.
  void search(uint32_t node_index, const float* query, float cell_distance, float* offsets,
              NearestCandidates<uint32_t>& found) const {
    const Node& node = nodes[node_index];
    if (node.axis == kLeaf) {
      for (uint32_t i = node.right_or_begin; i < node.end; ++i) {
        const float* p = entries[i].position;
        const float dx = query[0] - p[0], dy = query[1] - p[1], dz = query[2] - p[2];
        const float distance = dx * dx + dy * dy + dz * dz;
        if (distance < found.worst) found.add(distance, entries[i].index);
      }
      return;
    }
    const float value = query[node.axis];
    const float to_left = value - node.left_max, to_right = node.right_min - value;
    const bool left_first = to_left < to_right;  // nearer the left cell's side
    const uint32_t near = left_first ? node_index + 1 : node.right_or_begin;
    const uint32_t far = left_first ? node.right_or_begin : node_index + 1;
    search(near, query, cell_distance, offsets, found);
    const float gap = left_first ? to_right : to_left;
    const float far_offset = gap > 0.f ? gap * gap : 0.f;
    const float saved = offsets[node.axis];
    const float far_distance = cell_distance + far_offset - saved;
    if (far_distance <= found.worst) {
      offsets[node.axis] = far_offset;
      search(far, query, far_distance, offsets, found);
      offsets[node.axis] = saved;
    }
  }
};

PointKdTree::PointKdTree() = default;
PointKdTree::~PointKdTree() = default;
PointKdTree::PointKdTree(PointKdTree&&) noexcept = default;
PointKdTree& PointKdTree::operator=(PointKdTree&&) noexcept = default;

void PointKdTree::build(CloudConstPtr cloud) {
  cloud_ = std::move(cloud);
  if (!cloud_ || cloud_->empty()) {
    index_.reset();
    return;
  }
  if (!index_) index_ = std::make_unique<Index>();
  index_->assign(*cloud_);
}

int PointKdTree::nearest(const Eigen::Vector3f& query, int k, uint32_t* indices,
                         float* squared_distances, float max_squared_distance) const {
  if (!index_ || k <= 0) return 0;
  // Points must beat `worst` strictly: start just above the bound to include it.
  NearestCandidates<uint32_t> found{
      k, 0, indices, squared_distances,
      std::nextafter(max_squared_distance, std::numeric_limits<float>::infinity())};
  float offsets[3] = {0.f, 0.f, 0.f};
  index_->search(0, query.data(), 0.f, offsets, found);
  return found.count;
}

bool PointKdTree::empty() const {
  return !index_;
}

}  // namespace adaptive_lego_loam
