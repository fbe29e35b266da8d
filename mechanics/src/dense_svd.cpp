#include "dense_svd.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" void dgesdd_(const char* jobz, const int* m, const int* n, double* a, const int* lda, double* s,
                        double* u, const int* ldu, double* vt, const int* ldvt, double* work, const int* lwork,
                        int* iwork, int* info, std::size_t jobz_length);

namespace phedra {

RightSingular right_singular(const Eigen::MatrixXd& a) {
  const int m = static_cast<int>(a.rows());
  const int n = static_cast<int>(a.cols());
  const int k = std::min(m, n);
  RightSingular r;
  r.values.resize(k);
  if (n == 0) return r;
  if (m == 0) {
    r.vectors = Eigen::MatrixXd::Identity(n, n);
    return r;
  }
  Eigen::MatrixXd work_a = a;  // dgesdd overwrites its input
  // V is wanted whole (n x n); U only as far as LAPACK needs it: m x n when the
  // rows are at least the columns ('S': V^T is then n x n), else m x m ('A').
  const char job = m >= n ? 'S' : 'A';
  const int u_columns = m >= n ? n : m;
  Eigen::MatrixXd u(m, u_columns);
  Eigen::MatrixXd vt(n, n);
  std::vector<int> iwork(8 * static_cast<std::size_t>(k));
  int info = 0;
  int lwork = -1;
  double size = 0.0;
  dgesdd_(&job, &m, &n, work_a.data(), &m, r.values.data(), u.data(), &m, vt.data(), &n, &size, &lwork,
          iwork.data(), &info, 1);
  lwork = static_cast<int>(size) + 1;
  std::vector<double> work(static_cast<std::size_t>(lwork));
  dgesdd_(&job, &m, &n, work_a.data(), &m, r.values.data(), u.data(), &m, vt.data(), &n, work.data(), &lwork,
          iwork.data(), &info, 1);
  if (info != 0) {
    throw std::runtime_error("the singular value decomposition of the compatibility matrix failed (LAPACK dgesdd info " +
                             std::to_string(info) + ")");
  }
  r.vectors = vt.transpose();
  return r;
}

}  // namespace phedra
