#include "node_cholesky.h"

#include "phedra/errors.h"

#ifdef PHEDRA_CHOLMOD
#include "cholmod_memory.h"
#include "cholmod_threads.h"
#include "supernodal_solve.h"

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <vector>
#else
#include <Eigen/SparseCholesky>
#endif

namespace phedra {

#ifdef PHEDRA_CHOLMOD
namespace {

/// CHOLMOD's view of an Eigen matrix (compressed, sorted, int indices); stype 1:
/// the upper triangle is read, the lower ignored (CHOLMOD permutes an upper
/// triangle with one transpose, a lower one with two: cholmod_factorize.c).
cholmod_sparse view(const Eigen::SparseMatrix<double>& a) {
  cholmod_sparse v;
  std::memset(&v, 0, sizeof v);
  v.nrow = static_cast<std::size_t>(a.rows());
  v.ncol = static_cast<std::size_t>(a.cols());
  v.nzmax = static_cast<std::size_t>(a.nonZeros());
  v.p = const_cast<int*>(a.outerIndexPtr());
  v.i = const_cast<int*>(a.innerIndexPtr());
  v.x = const_cast<double*>(a.valuePtr());
  v.stype = 1;
  v.itype = CHOLMOD_INT;
  v.xtype = CHOLMOD_REAL;
  v.dtype = CHOLMOD_DOUBLE;
  v.sorted = 1;
  v.packed = 1;
  return v;
}

/// Node graphs of this many nodes and more are ordered by both AMD and METIS.
constexpr int both_orderings_from = 1000;

/// The node graph (node i: rows 3i .. 3i+2) ordered by AMD and, from
/// `both_orderings_from` nodes, also by METIS's nested dissection, CHOLMOD keeping
/// the one of fewer entries in the factor; each node's rows then kept together.
/// Empty when the rows are not node triples or the ordering fails (CHOLMOD then
/// orders the rows itself). CHOLMOD's default strategy tries METIS only when AMD's
/// factor has 500 flops an entry or more, a test the node graph passes three times
/// more easily than the matrix (27 flops a node's, 9 entries): it kept AMD on the
/// 10^4-panel array's corner model (the mobility), 9.4e9 flops against METIS's 2.4e9.
std::vector<int> node_ordering(const Eigen::SparseMatrix<double>& a, cholmod_common& common) {
  const Eigen::Index n = a.rows();
  if (n % 3 != 0 || n == 0) return {};
  const int nodes = static_cast<int>(n / 3);
  std::vector<int> start(static_cast<std::size_t>(nodes) + 1, 0), neighbours;
  neighbours.reserve(static_cast<std::size_t>(a.nonZeros() / 9 + nodes));
  for (int node = 0; node < nodes; ++node) {
    const std::size_t from = neighbours.size();
    for (int r = 0; r < 3; ++r) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, 3 * node + r); it; ++it) {
        const int other = static_cast<int>(it.row() / 3);
        if (other < node) neighbours.push_back(other);  // the upper triangle (a's lower one, if stored, is not read)
      }
    }
    std::sort(neighbours.begin() + static_cast<std::ptrdiff_t>(from), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin() + static_cast<std::ptrdiff_t>(from), neighbours.end()),
                     neighbours.end());
    start[static_cast<std::size_t>(node) + 1] = static_cast<int>(neighbours.size());
  }
  cholmod_sparse graph;
  std::memset(&graph, 0, sizeof graph);
  graph.nrow = graph.ncol = static_cast<std::size_t>(nodes);
  graph.nzmax = neighbours.size();
  graph.p = start.data();
  graph.i = neighbours.data();
  graph.stype = 1;  // symmetric, its upper triangle stored
  graph.itype = CHOLMOD_INT;
  graph.xtype = CHOLMOD_PATTERN;
  graph.dtype = CHOLMOD_DOUBLE;
  graph.sorted = 1;
  graph.packed = 1;
  const int default_methods = common.nmethods;
  if (nodes >= both_orderings_from) {
    common.nmethods = 2;
    common.method[0].ordering = CHOLMOD_AMD;
    common.method[1].ordering = CHOLMOD_METIS;
  }
  cholmod_factor* symbolic = cholmod_analyze(&graph, &common);
  common.nmethods = default_methods;
  if (symbolic == nullptr) return {};
  const int* node_order = static_cast<const int*>(symbolic->Perm);
  std::vector<int> order(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < static_cast<std::size_t>(nodes); ++k) {
    for (int r = 0; r < 3; ++r) order[3 * k + static_cast<std::size_t>(r)] = 3 * node_order[k] + r;
  }
  cholmod_free_factor(&symbolic, &common);
  return order;
}

}  // namespace

struct NodeCholesky::Factor {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  SupernodalFactor supernodal;
  std::vector<int> permutation;   // row k of the factor is row permutation[k] of a
  mutable std::vector<double> permuted, work;
  double entries = 0.0;

  Factor(const Eigen::SparseMatrix<double>& a, double shift) {
    cholmod_on_huge_pages();
    cholmod_start(&common);
    common.print = 0;  // its messages would reach standard output; failures are thrown below
    common.supernodal = CHOLMOD_SIMPLICIAL;  // the node graph's analysis: only its ordering is kept
    std::vector<int> order = node_ordering(a, common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    cholmod_sparse matrix = view(a);
    if (!order.empty()) {
      common.nmethods = 1;
      common.method[0].ordering = CHOLMOD_GIVEN;
      common.postorder = 1;
      factor = cholmod_analyze_p(&matrix, order.data(), nullptr, 0, &common);
    } else {
      factor = cholmod_analyze(&matrix, &common);
    }
    if (factor == nullptr) fail("its analysis failed (CHOLMOD status " + std::to_string(common.status) + ")");
    entries = common.lnz;
    {
      const OpenMPRegionsSerial one_thread;  // CHOLMOD's fixed 4-thread loops (cholmod_threads.h)
      double beta[2] = {shift, 0.0};  // a + shift I, a left as it is
      cholmod_factorize_p(&matrix, beta, nullptr, 0, factor, &common);
    }
    if (common.status == CHOLMOD_NOT_POSDEF) fail("the matrix is not positive definite");
    if (common.status != CHOLMOD_OK || !factor->is_super || !factor->is_ll || factor->itype != CHOLMOD_INT) {
      fail("CHOLMOD status " + std::to_string(common.status));
    }
    supernodal = {static_cast<int>(factor->nsuper), static_cast<const int*>(factor->super),
                  static_cast<const int*>(factor->pi),  static_cast<const int*>(factor->px),
                  static_cast<const int*>(factor->s),   static_cast<const double*>(factor->x)};
    const int* perm = static_cast<const int*>(factor->Perm);
    permutation.assign(perm, perm + a.rows());
    permuted.resize(4 * static_cast<std::size_t>(a.rows()));
    work.resize(4 * static_cast<std::size_t>(a.rows()));
  }
  ~Factor() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  Factor(const Factor&) = delete;
  Factor& operator=(const Factor&) = delete;

  [[noreturn]] void fail(const std::string& why) {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
    throw Error(ExitCode::internal, "stiffness: the Cholesky factorization of K + delta I failed: " + why);
  }

  void solve(const double* in, double* out) const {
    const std::size_t n = permutation.size();
    for (std::size_t k = 0; k < n; ++k) permuted[k] = in[permutation[k]];
    supernodal_solve(supernodal, permuted.data(), work.data());
    for (std::size_t k = 0; k < n; ++k) out[permutation[k]] = permuted[k];
  }

  void solve4(const double* in, double* out) const {
    const std::size_t n = permutation.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t row = static_cast<std::size_t>(permutation[k]);
      for (std::size_t r = 0; r < 4; ++r) permuted[4 * k + r] = in[r * n + row];
    }
    supernodal_solve4(supernodal, permuted.data(), work.data());
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t row = static_cast<std::size_t>(permutation[k]);
      for (std::size_t r = 0; r < 4; ++r) out[r * n + row] = permuted[4 * k + r];
    }
  }
};
#else
struct NodeCholesky::Factor {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::AMDOrdering<int>> ldlt;
  double entries = 0.0;
  Factor(const Eigen::SparseMatrix<double>& a, double shift) {
    ldlt.setShift(shift);
    ldlt.compute(a);
    entries = static_cast<double>(ldlt.matrixL().nestedExpression().nonZeros() + a.rows());
    if (ldlt.info() != Eigen::Success) {
      throw Error(ExitCode::internal, "stiffness: the Cholesky factorization of K + delta I failed");
    }
  }
  void solve(const double* in, double* out) const {
    const Eigen::Index n = ldlt.rows();
    const Eigen::VectorXd x = ldlt.solve(Eigen::Map<const Eigen::VectorXd>(in, n));
    Eigen::Map<Eigen::VectorXd>(out, n) = x;
  }
  void solve4(const double* in, double* out) const {
    const Eigen::Index n = ldlt.rows();
    for (Eigen::Index r = 0; r < 4; ++r) solve(in + r * n, out + r * n);
  }
};
#endif

NodeCholesky::NodeCholesky(const Eigen::SparseMatrix<double>& a, double shift)
    : factor_(std::make_unique<Factor>(a, shift)) {}
NodeCholesky::~NodeCholesky() = default;

void NodeCholesky::solve(const double* in, double* out) const { factor_->solve(in, out); }
void NodeCholesky::solve4(const double* in, double* out) const { factor_->solve4(in, out); }
double NodeCholesky::factor_entries() const { return factor_->entries; }

}  // namespace phedra
