#pragma once
// The Cholesky factor of a stiffness matrix (3 rows a node), for the
// shift-invert eigen-solver's repeated solves (internal to mechanics/).
//
// With CHOLMOD (native builds): the nodes ordered by AMD or, on graphs of 1000
// nodes and more, by the better of AMD and METIS's nested dissection (a third of
// the rows CHOLMOD's own analysis orders: 0.12 s instead of 0.21 s on the
// 10^4-panel array, the same fill within 2 %), each node's three rows kept
// together; the supernodal numeric
// factorization on the calling thread (cholmod_threads.h) and on huge pages
// (cholmod_memory.h); the solves by supernodal_solve.h. Elsewhere (WebAssembly)
// Eigen's simplicial LDL^T with AMD.
#include <Eigen/Sparse>

#include <memory>

namespace phedra {

class NodeCholesky {
 public:
  /// Factorizes a + shift I (symmetric positive definite; only a's upper
  /// triangle is read, its whole diagonal stored, its rows in node triples). Throws
  /// Error(internal) when it is not positive definite or memory runs out.
  explicit NodeCholesky(const Eigen::SparseMatrix<double>& a, double shift = 0.0);
  ~NodeCholesky();
  NodeCholesky(const NodeCholesky&) = delete;
  NodeCholesky& operator=(const NodeCholesky&) = delete;

  /// out = (a + shift I)^-1 in (in and out may be the same array). Not for concurrent calls
  /// on one object (its work arrays are its own).
  void solve(const double* in, double* out) const;
  /// The same for four right-hand sides, each a column of `a.rows()` values
  /// (column-major, in and out the same array or apart): about the cost of one
  /// solve with CHOLMOD (supernodal_solve4).
  void solve4(const double* in, double* out) const;
  /// The factor's entries (its lower triangle and diagonal): what the ordering decides.
  double factor_entries() const;

 private:
  struct Factor;
  std::unique_ptr<Factor> factor_;
};

}  // namespace phedra
