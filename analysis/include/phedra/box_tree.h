#pragma once
// A bounding-volume hierarchy over axis-aligned boxes (median splits along the
// longest axis): the broad phase of the collision tests. Panels of very
// different sizes (long boundary panels next to small ones) cost it nothing
// extra, unlike a uniform grid.

#include "phedra/vector_types.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace phedra {

struct Box {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  bool overlaps(const Box& other) const {
    return !((lo.array() > other.hi.array()).any() || (other.lo.array() > hi.array()).any());
  }
};

class BoxTree {
 public:
  explicit BoxTree(const std::vector<Box>& boxes);

  /// The indices of the boxes that overlap `box` (touching counts), unsorted.
  void overlapping(const Box& box, std::vector<std::size_t>& out) const;

  /// Calls visit(i, j) (i < j) once for every pair of overlapping boxes, in an
  /// order fixed by the boxes, until it returns false: a traversal of the tree
  /// against itself.
  template <class Visit>
  void for_each_pair(Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<std::pair<std::size_t, std::size_t>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      const Node& na = nodes_[a];
      const Node& nb = nodes_[b];
      if (a != b && !na.box.overlaps(nb.box)) continue;
      const bool leaf_a = na.left == 0, leaf_b = nb.left == 0;
      if (leaf_a && leaf_b) {
        for (std::size_t p = na.begin; p < na.end; ++p) {
          for (std::size_t q = a == b ? p + 1 : nb.begin; q < nb.end; ++q) {
            const std::size_t i = order_[p], j = order_[q];
            if (!boxes_[i].overlaps(boxes_[j])) continue;
            if (!visit(std::min(i, j), std::max(i, j))) return;
          }
        }
      } else if (a == b) {  // a node against itself: its children against themselves and each other
        stack.push_back({na.right, na.right});
        stack.push_back({na.left, na.right});
        stack.push_back({na.left, na.left});
      } else if (leaf_b || (!leaf_a && na.end - na.begin >= nb.end - nb.begin)) {
        stack.push_back({na.right, b});
        stack.push_back({na.left, b});
      } else {
        stack.push_back({a, nb.right});
        stack.push_back({a, nb.left});
      }
    }
  }

 private:
  struct Node {
    Box box;
    std::size_t begin = 0, end = 0;  ///< leaf: order_[begin, end)
    std::size_t left = 0, right = 0; ///< inner: children (left = 0 for a leaf; the root is 0)
  };
  std::size_t build(std::size_t begin, std::size_t end);

  const std::vector<Box>& boxes_;
  std::vector<std::size_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace phedra
