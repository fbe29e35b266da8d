#include "vertex_nodes.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace phedra {

std::optional<std::vector<std::uint32_t>> vertex_nodes(const FoldEnergy& fold, double rest_t) {
  const Assembly& a = fold.design().assembly;
  const double lo = a.flexion_interval().lower.t, hi = a.flexion_interval().upper.t;
  const std::array<double, 3> ts{rest_t, lo + 0.23 * (hi - lo), lo + 0.71 * (hi - lo)};
  std::array<std::vector<Points>, 3> members;
  std::array<Points, 3> nodes;
  FoldEnergy::Scratch scratch;
  for (std::size_t k = 0; k < ts.size(); ++k) {
    members[k] = a.evaluate(ts[k]).members;
    fold.nodes_at(ts[k], scratch);
    nodes[k] = scratch.x;
  }
  const double tolerance = 1e-9 * a.model_size();
  // The nodes in order along a direction no grid or plane of a design lies across
  // (along x, an axis-aligned grid has whole planes of nodes at one key).
  const Vec3 along = Vec3(0.5773, 0.6121, 0.5404).normalized();
  std::vector<double> key(nodes[0].size());
  for (std::size_t n = 0; n < key.size(); ++n) key[n] = along.dot(nodes[0][n]);
  std::vector<std::uint32_t> order(key.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) { return key[p] < key[q]; });
  std::vector<std::uint32_t> out;
  for (std::size_t m = 0; m < members[0].size(); ++m) {
    for (std::size_t v = 0; v < members[0][m].size(); ++v) {
      // |along . (p - q)| <= |p - q|: a node within the tolerance has its key within it.
      const double at = along.dot(members[0][m][v]);
      auto it = std::lower_bound(order.begin(), order.end(), at - tolerance,
                                 [&](std::uint32_t n, double bound) { return key[n] < bound; });
      std::optional<std::uint32_t> found;
      for (; it != order.end() && key[*it] <= at + tolerance && !found; ++it) {
        bool near = true;
        for (std::size_t k = 0; k < ts.size() && near; ++k) near = (nodes[k][*it] - members[k][m][v]).norm() <= tolerance;
        if (near) found = *it;
      }
      if (!found) return std::nullopt;
      out.push_back(*found);
    }
  }
  return out;
}

}  // namespace phedra
