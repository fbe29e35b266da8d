#pragma once
// The tangent stiffness's smallest eigenpairs (unit mass, free-free) and how
// they relate to the exact motion (docs/design.md, "Mechanics"):
//
// - rigid-body modes: eigenvalues under 1e-9 of the largest. The six rigid
//   motions of the nodes (translations, rotations about their centroid) are
//   known exactly and are deflated; the eigen-solver (Spectra, shift-invert on
//   a sparse Cholesky factor) finds the others, and any of them under the
//   threshold counts as rigid too (a piece held by nothing);
// - motion alignment: |cos| between the first non-rigid mode and the exact
//   velocity dX/dt (n5b8 centres included), both with the rigid motions
//   projected out; gap: the second non-rigid eigenvalue over the first; motion
//   stiffness: the Rayleigh quotient v^T K v / v^T v of that velocity.

#include "phedra/bar_hinge_model.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <optional>
#include <vector>

namespace phedra {

/// An orthonormal basis (3 n x 6) of the rigid motions of the points x:
/// translations and infinitesimal rotations about their centroid.
Eigen::MatrixXd rigid_motion_basis(const Points& x);

/// v with the rigid motions of x projected out.
Eigen::VectorXd without_rigid_motions(const Eigen::VectorXd& v, const Eigen::MatrixXd& rigid);

struct Eigenpairs {
  Eigen::VectorXd values;   ///< ascending
  Eigen::MatrixXd vectors;  ///< unit columns
};

/// The `count` smallest eigenpairs of the symmetric positive semidefinite K in
/// the complement of the columns of `deflated` (orthonormal, K deflated = 0):
/// dense for small matrices, else Spectra's shift-invert with a sparse Cholesky
/// factor of K + delta I. Only K's upper triangle (diagonal included) is read:
/// the whole matrix or BarHingeModel::stiffness_upper() alike. Throws
/// Error(internal) when the solver does not converge.
Eigenpairs smallest_eigenpairs(const Eigen::SparseMatrix<double>& k, const Eigen::MatrixXd& deflated, std::size_t count);

/// The largest eigenvalue of K (Lanczos, to 1e-10 relative); its upper triangle read.
double largest_eigenvalue(const Eigen::SparseMatrix<double>& k);

/// The relative size under which an eigenvalue is a rigid-body mode's.
inline constexpr double rigid_body_threshold = 1e-9;

struct ModeAnalysis {
  double t = 0.0;
  std::size_t nodes = 0, bars = 0, folds = 0, bends = 0;
  std::size_t rigid_body_modes = 0;
  double largest_eigenvalue = 0.0;
  Eigen::VectorXd eigenvalues;  ///< the smallest non-rigid ones, ascending
  Eigen::MatrixXd modes;        ///< their eigenvectors (3 x nodes each, unit, sign: first large entry positive)
  /// Against the exact velocity (none at a flexion limit, where it is infinite):
  std::optional<double> motion_alignment;  ///< |cos(mode 1, dX/dt)|
  std::optional<double> motion_stiffness;  ///< v^T K v / v^T v
  /// The share of the velocity in the span of the first 1, 2, ... modes (norm ratio).
  std::vector<double> motion_in_span;
  std::optional<double> gap;               ///< eigenvalue 2 / eigenvalue 1
  Eigen::VectorXd velocity;                ///< dX/dt of the nodes, rigid motions projected out (empty at a limit)
};

/// How many non-rigid modes a model can have: 3 x nodes - 6.
std::size_t mode_capacity(const BarHingeModel& model);

/// The analysis of `model`; `velocity` (3 x nodes, the nodes' dX/dt) if known.
/// Throws InvalidInputError("--modes") when `modes` exceeds what the model has.
ModeAnalysis analyze_modes(const BarHingeModel& model, const std::optional<Eigen::VectorXd>& velocity,
                           std::size_t modes);

/// The model of `design` at t and its analysis (with the exact velocity).
ModeAnalysis analyze_modes(const Design& design, double t, const StiffnessOptions& options, std::size_t modes);

/// Points as one vector (x0, y0, z0, x1, ...).
Eigen::VectorXd flatten(const Points& x);

}  // namespace phedra
