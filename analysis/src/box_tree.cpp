#include "phedra/box_tree.h"

#include <algorithm>

namespace phedra {
namespace {

constexpr std::size_t leaf_size = 4;

}  // namespace

BoxTree::BoxTree(const std::vector<Box>& boxes) : boxes_(boxes), order_(boxes.size()) {
  for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = k;
  nodes_.reserve(2 * (boxes.size() / leaf_size + 1));
  if (!boxes.empty()) build(0, boxes.size());
}

std::size_t BoxTree::build(std::size_t begin, std::size_t end) {
  const std::size_t index = nodes_.size();
  nodes_.push_back({});
  Box box = boxes_[order_[begin]];
  for (std::size_t k = begin + 1; k < end; ++k) {
    box.lo = box.lo.cwiseMin(boxes_[order_[k]].lo);
    box.hi = box.hi.cwiseMax(boxes_[order_[k]].hi);
  }
  nodes_[index].box = box;
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  if (end - begin <= leaf_size) return index;
  // Split at the median of the box centres along the longest axis.
  int axis = 0;
  (box.hi - box.lo).maxCoeff(&axis);
  const std::size_t middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(begin), order_.begin() + static_cast<std::ptrdiff_t>(middle),
                   order_.begin() + static_cast<std::ptrdiff_t>(end), [&](std::size_t a, std::size_t b) {
                     return boxes_[a].lo[axis] + boxes_[a].hi[axis] < boxes_[b].lo[axis] + boxes_[b].hi[axis];
                   });
  const std::size_t left = build(begin, middle);
  const std::size_t right = build(middle, end);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void BoxTree::overlapping(const Box& box, std::vector<std::size_t>& out) const {
  if (nodes_.empty()) return;
  std::size_t stack[128];
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.overlaps(box)) continue;
    if (node.left == 0) {
      for (std::size_t k = node.begin; k < node.end; ++k) {
        if (boxes_[order_[k]].overlaps(box)) out.push_back(order_[k]);
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
}

}  // namespace phedra
