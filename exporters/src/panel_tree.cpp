#include "phedra/panel_tree.h"

#include <algorithm>
#include <deque>
#include <map>

namespace phedra {
namespace {

/// Orthonormal frame (columns) of the triangle a, b, c: e1 along b - a, e3 normal.
Mat3 triangle_frame(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = (b - a).normalized();
  const Vec3 e3 = (b - a).cross(c - a).normalized();
  Mat3 f;
  f.col(0) = e1;
  f.col(1) = e3.cross(e1);
  f.col(2) = e3;
  return f;
}

}  // namespace

PanelTree::PanelTree(const std::vector<Quad>& faces, std::span<const Vec3> reference) : faces_(faces) {
  const std::size_t count = faces.size();
  parent_.assign(count, SIZE_MAX);
  children_.assign(count, {});
  origin_.assign(count, Vec3::Zero());
  local_.assign(count, {});
  frame_corners_.assign(count, {0, 1, 2});
  reference_frame_.assign(count, Mat3::Identity());
  // Hinges: faces sharing an (undirected) edge.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> edge_faces;
  for (std::size_t f = 0; f < count; ++f) {
    for (int e = 0; e < 4; ++e) {
      const std::size_t a = faces[f][e], b = faces[f][(e + 1) % 4];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  std::vector<std::vector<std::pair<std::size_t, std::pair<std::size_t, std::size_t>>>> neighbours(count);
  for (const auto& [edge, list] : edge_faces) {
    for (std::size_t x = 0; x < list.size(); ++x) {
      for (std::size_t y = 0; y < list.size(); ++y) {
        if (x != y) neighbours[list[x]].push_back({list[y], edge});
      }
    }
  }
  // Hinge distances from `from` to every face of its component (SIZE_MAX elsewhere), and the faces reached.
  auto distances = [&](std::size_t from, std::vector<std::size_t>& reached) {
    std::vector<std::size_t> d(count, SIZE_MAX);
    d[from] = 0;
    reached = {from};
    for (std::size_t i = 0; i < reached.size(); ++i) {
      for (const auto& [g, edge] : neighbours[reached[i]]) {
        if (d[g] != SIZE_MAX) continue;
        d[g] = d[reached[i]] + 1;
        reached.push_back(g);
      }
    }
    return d;
  };
  std::vector<bool> seen(count, false);
  for (std::size_t first = 0; first < count; ++first) {
    if (seen[first]) continue;
    // The middle of the component: distances from a few extreme faces (the
    // farthest from the first face, then each time the face farthest from all
    // extremes so far: the corners of a grid), and the face whose largest
    // distance to them is smallest. For a grid of panels that is its centre.
    std::vector<std::size_t> component;
    distances(first, component);
    std::vector<std::size_t> nearest(count, SIZE_MAX), farthest(count, 0), total(count, 0);
    std::size_t next = component.back();
    for (int k = 0; k < 6; ++k) {
      std::vector<std::size_t> reached;
      const std::vector<std::size_t> d = distances(next, reached);
      for (std::size_t f : component) {
        nearest[f] = std::min(nearest[f], d[f]);
        farthest[f] = std::max(farthest[f], d[f]);
        total[f] += d[f];
      }
      next = *std::max_element(component.begin(), component.end(),
                               [&](std::size_t x, std::size_t y) { return nearest[x] < nearest[y]; });
      if (nearest[next] == 0) break;  // every face is an extreme already (tiny components)
    }
    // The extremes bound each face's eccentricity from below; the best few
    // candidates get their exact eccentricity (a breadth-first sweep each).
    std::vector<std::size_t> candidates = component;
    const std::size_t keep = std::min<std::size_t>(8, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep), candidates.end(),
                      [&](std::size_t x, std::size_t y) {
                        return std::pair(farthest[x], total[x]) < std::pair(farthest[y], total[y]);
                      });
    std::size_t start = candidates.front(), best = SIZE_MAX;
    for (std::size_t k = 0; k < keep; ++k) {
      std::vector<std::size_t> reached;
      const std::vector<std::size_t> d = distances(candidates[k], reached);
      if (d[reached.back()] < best) best = d[reached.back()], start = candidates[k];
    }
    seen[start] = true;
    roots_.push_back(start);
    origin_[start] = reference[faces[start][0]];
    std::deque<std::pair<std::size_t, std::size_t>> queue{{start, 1}};
    while (!queue.empty()) {
      const auto [f, level] = queue.front();
      queue.pop_front();
      order_.push_back(f);
      depth_ = std::max(depth_, level);
      for (const auto& [g, edge] : neighbours[f]) {
        if (seen[g]) continue;
        seen[g] = true;
        parent_[g] = f;
        children_[f].push_back(g);
        origin_[g] = 0.5 * (reference[edge.first] + reference[edge.second]);
        queue.push_back({g, level + 1});
      }
    }
  }
  for (std::size_t f = 0; f < count; ++f) {
    for (int k = 0; k < 4; ++k) local_[f][k] = reference[faces[f][k]] - origin_[f];
    double best = -1;
    for (int skip = 0; skip < 4; ++skip) {
      const int a = (skip + 1) % 4, b = (skip + 2) % 4, c = (skip + 3) % 4;
      const double area = (reference[faces[f][b]] - reference[faces[f][a]])
                              .cross(reference[faces[f][c]] - reference[faces[f][a]])
                              .norm();
      if (area > best) {
        best = area;
        frame_corners_[f] = {a, b, c};
      }
    }
    const auto& k = frame_corners_[f];
    reference_frame_[f] = triangle_frame(reference[faces[f][k[0]]], reference[faces[f][k[1]]], reference[faces[f][k[2]]]);
  }
}

RigidPose PanelTree::world_pose(std::size_t f, std::span<const Vec3> positions) const {
  // M maps the reference panel onto the current one; the node pose is M after
  // moving the origin: pose(x) = M(origin + x).
  const auto& k = frame_corners_[f];
  const Vec3& a = positions[faces_[f][k[0]]];
  const Mat3 now = triangle_frame(a, positions[faces_[f][k[1]]], positions[faces_[f][k[2]]]);
  const Mat3 rotation = now * reference_frame_[f].transpose();
  const Vec3 reference_corner = origin_[f] + local_[f][k[0]];
  RigidPose pose;
  pose.rotation = Eigen::Quaterniond(rotation).normalized();
  pose.translation = a + rotation * (origin_[f] - reference_corner);
  return pose;
}

std::vector<RigidPose> PanelTree::local_poses(std::span<const Vec3> positions) const {
  std::vector<RigidPose> world(panels()), local(panels());
  for (std::size_t f = 0; f < panels(); ++f) world[f] = world_pose(f, positions);
  for (std::size_t f = 0; f < panels(); ++f) {
    if (parent_[f] == SIZE_MAX) {
      local[f] = world[f];
    } else {
      local[f].rotation = (world[parent_[f]].rotation.conjugate() * world[f].rotation).normalized();
      local[f].translation = origin_[f] - origin_[parent_[f]];
    }
  }
  return local;
}

std::vector<RigidPose> PanelTree::world_poses(const std::vector<RigidPose>& local) const {
  std::vector<RigidPose> world;
  world_poses(local, world);
  return world;
}

void PanelTree::world_poses(const std::vector<RigidPose>& local, std::vector<RigidPose>& world) const {
  world.resize(panels());
  for (std::size_t f : order_) {
    if (parent_[f] == SIZE_MAX) {
      world[f] = local[f];
    } else {
      const RigidPose& p = world[parent_[f]];
      world[f].rotation = p.rotation * local[f].rotation;
      world[f].translation = p.apply(local[f].translation);
    }
  }
}

}  // namespace phedra
