#include "block_assembly.h"

#include "phedra/errors.h"

#include <algorithm>
#include <limits>
#include <string>

namespace phedra {

BlockAssembly::BlockAssembly(std::size_t nodes, const std::vector<std::span<const std::size_t>>& elements) {
  std::vector<std::vector<std::size_t>> neighbours(nodes);
  for (const auto& e : elements) {
    for (std::size_t c : e) {
      for (std::size_t r : e) {
        if (r <= c) neighbours[c].push_back(r);
      }
    }
  }
  start_.assign(nodes + 1, 0);
  for (std::size_t c = 0; c < nodes; ++c) {
    std::vector<std::size_t>& n = neighbours[c];
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    start_[c + 1] = start_[c] + n.size();
  }
  rows_.reserve(start_[nodes]);
  for (const auto& n : neighbours) rows_.insert(rows_.end(), n.begin(), n.end());
  values_.assign(9 * rows_.size(), 0.0);
}

std::size_t BlockAssembly::slot(std::size_t r, std::size_t c) const {
  const auto first = rows_.begin() + static_cast<std::ptrdiff_t>(start_[c]);
  const auto last = rows_.begin() + static_cast<std::ptrdiff_t>(start_[c + 1]);
  const auto at = std::lower_bound(first, last, r);
  if (at == last || *at != r) throw Error(ExitCode::internal, "stiffness: a block outside the assembled pattern");
  return static_cast<std::size_t>(at - rows_.begin());
}

void BlockAssembly::add(std::size_t r, std::size_t c, const Mat3& block) {
  double* v = &values_[9 * slot(r, c)];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) v[3 * j + i] += block(i, j);
}

Eigen::SparseMatrix<double> BlockAssembly::upper() const {
  const std::size_t nodes = start_.size() - 1;
  const Eigen::Index n = static_cast<Eigen::Index>(3 * nodes);
  std::size_t entries = values_.size();  // 9 a block, 6 a diagonal one
  for (std::size_t c = 0; c < nodes; ++c) {
    if (start_[c] < start_[c + 1] && rows_[start_[c + 1] - 1] == c) entries -= 3;
  }
  if (entries > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw Error(ExitCode::internal, "stiffness: " + std::to_string(entries) +
                                        " entries, more than a sparse matrix's int indices hold");
  }
  Eigen::SparseMatrix<double> k(n, n);
  k.resizeNonZeros(static_cast<Eigen::Index>(entries));
  int* outer = k.outerIndexPtr();
  int* inner = k.innerIndexPtr();
  double* value = k.valuePtr();
  std::size_t at = 0;
  for (std::size_t c = 0; c < nodes; ++c) {
    for (int j = 0; j < 3; ++j) {
      outer[3 * c + static_cast<std::size_t>(j)] = static_cast<int>(at);
      for (std::size_t b = start_[c]; b < start_[c + 1]; ++b) {
        for (int i = 0; i < (rows_[b] == c ? j + 1 : 3); ++i) {  // the diagonal block's upper triangle
          inner[at] = static_cast<int>(3 * rows_[b] + static_cast<std::size_t>(i));
          value[at] = values_[9 * b + 3 * static_cast<std::size_t>(j) + static_cast<std::size_t>(i)];
          ++at;
        }
      }
    }
  }
  outer[n] = static_cast<int>(at);
  return k;
}

}  // namespace phedra
