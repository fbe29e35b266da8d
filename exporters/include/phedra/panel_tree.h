#pragma once
// Rigid panels of a quad mesh nested along a spanning tree of its hinges: the
// node hierarchy of the animated glTF. A child panel's node sits on its hinge
// with the parent (origin on the hinge, constant offset), so between keyframes
// only its rotation about that hinge changes and tree hinges stay closed.

#include "phedra/grid_topology.h"
#include "phedra/vector_types.h"

#include <Eigen/Geometry>

#include <span>
#include <vector>

namespace phedra {

/// A rigid placement x -> rotation * x + translation.
struct RigidPose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
};

class PanelTree {
 public:
  /// `faces` index `reference` (positions at t*). Faces that share an edge are
  /// hinged; every connected component becomes one tree, breadth first from its
  /// middle (the face halfway along a longest shortest path: the shallowest tree
  /// up to one level, so float32 poses compose over half the chain).
  PanelTree(const std::vector<Quad>& faces, std::span<const Vec3> reference);

  std::size_t panels() const { return parent_.size(); }
  /// SIZE_MAX for a root.
  std::size_t parent(std::size_t panel) const { return parent_[panel]; }
  const std::vector<std::size_t>& children(std::size_t panel) const { return children_[panel]; }
  const std::vector<std::size_t>& roots() const { return roots_; }
  /// The face's mesh vertices.
  const Quad& face(std::size_t panel) const { return faces_[panel]; }
  /// Levels of the deepest tree (1 for a single panel).
  std::size_t depth() const { return depth_; }
  /// Panels in breadth-first order (parents before children).
  const std::vector<std::size_t>& order() const { return order_; }
  /// The node's origin at t*: a point of its hinge with the parent (the root: its first vertex).
  const Vec3& origin(std::size_t panel) const { return origin_[panel]; }
  /// Vertex k of the panel relative to its origin, at t*.
  const std::array<Vec3, 4>& local_vertices(std::size_t panel) const { return local_[panel]; }

  /// Local poses at one configuration (positions of the mesh vertices): a root's
  /// local pose is its world pose; a child's is its rotation relative to the
  /// parent with the constant offset origin(child) - origin(parent).
  std::vector<RigidPose> local_poses(std::span<const Vec3> positions) const;

  /// World poses from local ones (parents before children).
  std::vector<RigidPose> world_poses(const std::vector<RigidPose>& local) const;
  /// The same into `world` (resized; no allocation when it has the size already).
  void world_poses(const std::vector<RigidPose>& local, std::vector<RigidPose>& world) const;

 private:
  RigidPose world_pose(std::size_t panel, std::span<const Vec3> positions) const;

  std::vector<Quad> faces_;
  std::vector<std::size_t> parent_;
  std::vector<std::vector<std::size_t>> children_;
  std::vector<std::size_t> roots_, order_;
  std::size_t depth_ = 0;
  std::vector<Vec3> origin_;
  std::vector<std::array<Vec3, 4>> local_;
  std::vector<std::array<int, 3>> frame_corners_;  ///< best-conditioned corners for the panel's frame
  std::vector<Mat3> reference_frame_;              ///< orthonormal frame at t* (columns)
};

}  // namespace phedra
