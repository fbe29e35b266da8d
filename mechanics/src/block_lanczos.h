#pragma once
// The largest eigenpairs of a symmetric operator applied four vectors at a time
// (internal to mechanics/): the shift-invert eigen-solver's Krylov method.
//
// A solve with a supernodal Cholesky factor is bound by reading the factor:
// four right-hand sides cost about 1.2 single ones (node_cholesky.h), so a
// block Krylov space grows four vectors for the price of one. Block Lanczos
// with full reorthogonalization and Rayleigh-Ritz on the projected operator
// (no restart): on the 10^4-panel array the six smallest modes take 12 solves
// of four against Spectra's 23 single ones (docs/performance.md).
#include <Eigen/Dense>

#include <functional>
#include <optional>

namespace phedra {

/// Applies the operator to the four columns of `in`, into `out` (n x 4).
using ApplyFour = std::function<void(const Eigen::MatrixXd& in, Eigen::MatrixXd& out)>;

/// Ritz vectors (n x nev, unit, by decreasing Ritz value) of the nev largest
/// eigenvalues of the symmetric operator `apply`, from the block `start`
/// (n x 4, in the operator's range), each with a residual |A v - theta v| within
/// `tolerance` |theta|. Empty when the basis would exceed `max_basis` vectors
/// first or the Krylov space breaks down (the caller falls back to another method).
std::optional<Eigen::MatrixXd> block_lanczos_largest(const ApplyFour& apply, const Eigen::MatrixXd& start,
                                                     Eigen::Index nev, double tolerance, Eigen::Index max_basis);

}  // namespace phedra
