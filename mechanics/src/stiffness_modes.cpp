#include "phedra/stiffness_modes.h"

#include "phedra/errors.h"

#include "block_lanczos.h"
#include "node_cholesky.h"

#include <Eigen/Dense>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsShiftSolver.h>
#include <Spectra/SymEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>

namespace phedra {
namespace {

/// y = P (K - sigma I)^-1 P x, P the projection off the deflated columns; one
/// vector (Spectra's operator) or four (the block Lanczos's).
class DeflatedShiftSolve {
 public:
  using Scalar = double;
  DeflatedShiftSolve(const Eigen::SparseMatrix<double>& k, const Eigen::MatrixXd& deflated, double sigma)
      : k_(k), d_(deflated), projected_(k.rows()), projected4_(k.rows(), 4) {
    set_shift(sigma);
  }
  Eigen::Index rows() const { return k_.rows(); }
  Eigen::Index cols() const { return k_.cols(); }
  void set_shift(double sigma) {  // Spectra sets the shift it was given: factorized once
    if (factor_ && sigma == sigma_) return;
    factor_.reset();  // the old factor's memory back before the new one's
    factor_ = std::make_unique<NodeCholesky>(k_, -sigma);
    sigma_ = sigma;
  }
  void perform_op(const double* in, double* out) const {
    Eigen::Map<const Eigen::VectorXd> x(in, k_.rows());
    Eigen::Map<Eigen::VectorXd> y(out, k_.rows());
    project(x, projected_);
    factor_->solve(projected_.data(), out);
    project(y, y);
  }
  void perform_op4(const Eigen::MatrixXd& in, Eigen::MatrixXd& out) const {
    project(in, projected4_);
    out.resize(k_.rows(), 4);
    factor_->solve4(projected4_.data(), out.data());
    project(out, out);
  }
  template <typename In, typename Out>
  void project(const In& x, Out&& y) const {
    if (d_.cols() == 0) {
      y = x;
      return;
    }
    const Eigen::MatrixXd c = d_.transpose() * x;
    y = x - d_ * c;
  }

 private:
  const Eigen::SparseMatrix<double>& k_;
  const Eigen::MatrixXd& d_;
  double sigma_ = 0.0;
  std::unique_ptr<NodeCholesky> factor_;  // CHOLMOD's supernodal Cholesky; Eigen's in WebAssembly (node_cholesky.h)
  mutable Eigen::VectorXd projected_;
  mutable Eigen::MatrixXd projected4_;
};

/// An orthonormal basis of the complement of the (orthonormal) columns of d.
Eigen::MatrixXd complement(const Eigen::MatrixXd& d, Eigen::Index n) {
  if (d.cols() == 0) return Eigen::MatrixXd::Identity(n, n);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(d);
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
  return q.rightCols(n - d.cols());
}

Eigenpairs dense_smallest(const Eigen::SparseMatrix<double>& k, const Eigen::MatrixXd& deflated, std::size_t count) {
  const Eigen::MatrixXd q = complement(deflated, k.rows());
  const Eigen::MatrixXd reduced = q.transpose() * (k.selfadjointView<Eigen::Upper>() * q);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (reduced + reduced.transpose()));
  if (eig.info() != Eigen::Success) throw Error(ExitCode::internal, "stiffness: the dense eigen-solver failed");
  const Eigen::Index c = static_cast<Eigen::Index>(count);
  return {eig.eigenvalues().head(c), q * eig.eigenvectors().leftCols(c)};
}

}  // namespace

Eigen::VectorXd flatten(const Points& x) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) v.segment<3>(3 * static_cast<Eigen::Index>(i)) = x[i];
  return v;
}

Eigen::MatrixXd rigid_motion_basis(const Points& x) {
  const Eigen::Index n = static_cast<Eigen::Index>(x.size());
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : x) centroid += p;
  centroid /= static_cast<double>(n);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * n, 6);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 p = x[static_cast<std::size_t>(i)] - centroid;
    for (int a = 0; a < 3; ++a) {
      r(3 * i + a, a) = 1.0;
      const Vec3 w = Vec3::Unit(a).cross(p);
      r.block<3, 1>(3 * i, 3 + a) = w;
    }
  }
  // Orthonormal: thin QR (the columns are independent unless the points are collinear).
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(r);
  return qr.householderQ() * Eigen::MatrixXd::Identity(3 * n, 6);
}

Eigen::VectorXd without_rigid_motions(const Eigen::VectorXd& v, const Eigen::MatrixXd& rigid) {
  return v - rigid * (rigid.transpose() * v);
}

Eigenpairs smallest_eigenpairs(const Eigen::SparseMatrix<double>& k, const Eigen::MatrixXd& deflated, std::size_t count) {
  const Eigen::Index n = k.rows();
  const Eigen::Index available = n - deflated.cols();
  if (count == 0) return {Eigen::VectorXd(), Eigen::MatrixXd(n, 0)};
  const Eigen::Index nev = static_cast<Eigen::Index>(count);
  if (n <= 150 || 3 * nev + 20 > available) return dense_smallest(k, deflated, count);
  const double diagonal = k.diagonal().maxCoeff();
  const double sigma = -1e-10 * diagonal;
  DeflatedShiftSolve op(k, deflated, sigma);
  // Ritz residuals to 1e-6 of each Ritz value: a Ritz vector of residual r in K has
  // its Rayleigh quotient within |r|^2 / gap of the eigenvalue (relative error ~
  // tol^2 / relative gap, 1e-12 here) and its direction within tol / relative gap.
  constexpr double tolerance = 1e-6;
  // Block Lanczos first where solves dominate (four vectors a solve, block_lanczos.h):
  // on the 10^4-panel array 12 solves of four (0.56 s against Spectra's 23 single
  // ones, 0.72 s), the eigenvalues within 4e-11 of a run to 1e-12. Below 10^4 rows
  // the solves are cheap and Spectra's smaller basis is faster (the bench's 100-panel
  // tube: 0.24 s over 200 configurations against 0.30 s); beyond 16 eigenpairs its
  // unrestarted basis (at most 128 vectors here) would outgrow Spectra's restarted one.
  std::optional<Eigen::MatrixXd> vectors;
  const Eigen::Index max_basis = std::min<Eigen::Index>(128, (available - 8) / 4 * 4);
  if (n >= 10000 && nev <= 16 && max_basis >= nev + 8) {
    std::mt19937_64 rng(36);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    Eigen::MatrixXd start(n, 4);
    for (Eigen::Index i = 0; i < start.size(); ++i) start.data()[i] = uniform(rng);
    op.project(Eigen::MatrixXd(start), start);
    vectors = block_lanczos_largest([&](const Eigen::MatrixXd& in, Eigen::MatrixXd& out) { op.perform_op4(in, out); },
                                    start, nev, tolerance, max_basis);
  }
  if (!vectors) {
    // Spectra's Lanczos (one vector a solve): a Krylov space of nev + 16 (22 for
    // the usual 6); on the 10^4-panel array 23 solves (30 with nev + 14 and 1e-10).
    const Eigen::Index ncv = std::min<Eigen::Index>(available, std::max<Eigen::Index>(2 * nev + 1, nev + 16));
    Spectra::SymEigsShiftSolver<DeflatedShiftSolve> eigs(op, nev, ncv, sigma);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestMagn, 2000, tolerance, Spectra::SortRule::SmallestAlge);
    if (eigs.info() != Spectra::CompInfo::Successful) {
      throw Error(ExitCode::internal, "stiffness: the eigen-solver did not converge (" + std::to_string(count) +
                                          " eigenpairs of a " + std::to_string(n) + "-square matrix)");
    }
    vectors = eigs.eigenvectors();
  }
  Eigenpairs out{Eigen::VectorXd(nev), std::move(*vectors)};
  // Ascending, each value the Rayleigh quotient of its unit vector (quadratically accurate).
  std::vector<Eigen::Index> order(static_cast<std::size_t>(nev));
  for (Eigen::Index i = 0; i < nev; ++i) {
    out.vectors.col(i).normalize();
    out.values(i) = out.vectors.col(i).dot(k.selfadjointView<Eigen::Upper>() * out.vectors.col(i));
    order[static_cast<std::size_t>(i)] = i;
  }
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return out.values(a) < out.values(b); });
  Eigenpairs sorted{Eigen::VectorXd(nev), Eigen::MatrixXd(n, nev)};
  for (Eigen::Index i = 0; i < nev; ++i) {
    sorted.values(i) = out.values(order[static_cast<std::size_t>(i)]);
    sorted.vectors.col(i) = out.vectors.col(order[static_cast<std::size_t>(i)]);
  }
  return sorted;
}

double largest_eigenvalue(const Eigen::SparseMatrix<double>& k) {
  const Eigen::Index n = k.rows();
  if (n <= 150) {
    // The dense solver reads a lower triangle: K's upper one transposed.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(k.transpose()), Eigen::EigenvaluesOnly);
    return eig.eigenvalues()(n - 1);
  }
  Spectra::SparseSymMatProd<double, Eigen::Upper> op(k);  // the upper triangle read: half the memory
  // 12 vectors: 25 products on the 10^4-panel array (31 with 30), the same value to 1e-15.
  Spectra::SymEigsSolver<Spectra::SparseSymMatProd<double, Eigen::Upper>> eigs(op, 1, std::min<Eigen::Index>(n, 12));
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 2000, 1e-10);
  if (eigs.info() != Spectra::CompInfo::Successful) {
    throw Error(ExitCode::internal, "stiffness: the largest eigenvalue did not converge");
  }
  return eigs.eigenvalues()(0);
}

std::size_t mode_capacity(const BarHingeModel& model) { return 3 * model.node_count() - 6; }

ModeAnalysis analyze_modes(const BarHingeModel& model, const std::optional<Eigen::VectorXd>& velocity,
                           std::size_t modes) {
  const std::size_t capacity = mode_capacity(model);
  if (modes < 1 || modes > capacity) {
    throw InvalidInputError("--modes", "must be between 1 and " + std::to_string(capacity) +
                                           " (the model has " + std::to_string(model.node_count()) + " nodes: " +
                                           std::to_string(3 * model.node_count()) + " degrees of freedom less 6 rigid "
                                           "motions), got " + std::to_string(modes));
  }
  ModeAnalysis a;
  a.t = model.t();
  a.nodes = model.node_count();
  a.bars = model.bars().size();
  a.folds = model.fold_count();
  a.bends = model.bend_count();
  const Eigen::SparseMatrix<double> k = model.stiffness_upper();
  const Eigen::MatrixXd rigid = rigid_motion_basis(model.positions());
  a.largest_eigenvalue = largest_eigenvalue(k);
  const double threshold = rigid_body_threshold * a.largest_eigenvalue;
  // More than `modes` when some computed ones are under the threshold (extra rigid-body modes).
  Eigenpairs pairs;
  std::size_t small = 0;
  for (std::size_t wanted = modes;;) {
    pairs = smallest_eigenpairs(k, rigid, wanted);
    small = 0;
    while (small < wanted && pairs.values(static_cast<Eigen::Index>(small)) < threshold) ++small;
    if (wanted - small >= modes || wanted == capacity) break;
    wanted = std::min(capacity, std::max(2 * wanted, small + modes));  // doubling: few runs however many
  }
  a.rigid_body_modes = 6 + small;
  const Eigen::Index first = static_cast<Eigen::Index>(small);
  const Eigen::Index count = std::min<Eigen::Index>(static_cast<Eigen::Index>(modes), pairs.values.size() - first);
  a.eigenvalues = pairs.values.segment(first, count);
  a.modes = pairs.vectors.middleCols(first, count);
  for (Eigen::Index c = 0; c < count; ++c) {
    Eigen::Index largest;
    a.modes.col(c).cwiseAbs().maxCoeff(&largest);
    if (a.modes(largest, c) < 0.0) a.modes.col(c) *= -1.0;
  }
  if (count >= 2 && a.eigenvalues(0) > 0.0) a.gap = a.eigenvalues(1) / a.eigenvalues(0);
  if (velocity) {
    a.velocity = without_rigid_motions(*velocity, rigid);
    const double norm = a.velocity.norm();
    if (norm > 0.0) {
      const Eigen::VectorXd unit = a.velocity / norm;
      const Eigen::VectorXd first_mode = without_rigid_motions(a.modes.col(0), rigid);
      a.motion_alignment = std::abs(first_mode.dot(unit)) / first_mode.norm();
      a.motion_stiffness = unit.dot(k.selfadjointView<Eigen::Upper>() * unit);
      double share = 0.0;
      for (Eigen::Index c = 0; c < count; ++c) {
        const double p = a.modes.col(c).dot(unit);
        share += p * p;
        a.motion_in_span.push_back(std::sqrt(std::min(1.0, share)));
      }
    }
  }
  return a;
}

ModeAnalysis analyze_modes(const Design& design, double t, const StiffnessOptions& options, std::size_t modes) {
  AssemblyConfiguration c;
  std::vector<Points> rates;
  const bool finite = design.assembly.evaluate_rate(t, c, rates);
  const BarHingeModel model(design, c, options);
  std::optional<Eigen::VectorXd> velocity;
  if (finite) {
    Points v;
    model.node_rates(rates, v);
    velocity = flatten(v);
  }
  return analyze_modes(model, velocity, modes);
}

}  // namespace phedra
