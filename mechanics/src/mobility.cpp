#include "phedra/mobility.h"

#include "dense_svd.h"

#include "phedra/stiffness_modes.h"
#include "phedra/number_format.h"
#include "phedra/report_values.h"

#include <Eigen/QR>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>

namespace phedra {
namespace {

/// The rows of C over the corner nodes: edges and shorter diagonals as bars
/// (unit direction), bending hinges across the diagonals (gradient times length).
Eigen::SparseMatrix<double> compatibility(const ModelMesh& mesh) {
  const Points& x = mesh.positions;
  std::vector<Eigen::Triplet<double>> entries;
  std::map<std::pair<std::size_t, std::size_t>, bool> bars;
  Eigen::Index row = 0;
  auto bar = [&](std::size_t a, std::size_t b) {
    if (!bars.emplace(std::minmax(a, b), true).second) return;
    const Vec3 e = (x[b] - x[a]).normalized();
    for (int c = 0; c < 3; ++c) {
      entries.emplace_back(row, 3 * a + c, -e(c));
      entries.emplace_back(row, 3 * b + c, e(c));
    }
    ++row;
  };
  for (const ModelPanel& p : mesh.panels) {
    const std::vector<std::size_t>& v = p.corners;
    for (std::size_t k = 0; k < v.size(); ++k) bar(v[k], v[(k + 1) % v.size()]);
    if (v.size() == 3) continue;
    const std::size_t a = (x[v[2]] - x[v[0]]).norm() <= (x[v[3]] - x[v[1]]).norm() ? 0 : 1;
    bar(v[a], v[a + 2]);
    const std::array<std::size_t, 4> nodes{v[a], v[a + 2], v[a + 1], v[(a + 3) % 4]};
    const HingeNodes h{x[nodes[0]], x[nodes[1]], x[nodes[2]], x[nodes[3]]};
    const std::array<Vec3, 4> g = hinge_angle_gradient(h);
    const double length = (h.k - h.j).norm();
    for (int n = 0; n < 4; ++n) {
      for (int c = 0; c < 3; ++c) entries.emplace_back(row, 3 * nodes[n] + c, length * g[n](c));
    }
    ++row;
  }
  Eigen::SparseMatrix<double> c(row, 3 * static_cast<Eigen::Index>(x.size()));
  c.setFromTriplets(entries.begin(), entries.end());
  return c;
}

}  // namespace

Mobility mobility(const ModelMesh& mesh, const std::optional<Eigen::VectorXd>& velocity) {
  Mobility m;
  m.nodes = mesh.positions.size();
  const Points& corners = mesh.positions;
  const Eigen::SparseMatrix<double> c = compatibility(mesh);
  m.constraints = static_cast<std::size_t>(c.rows());
  const Eigen::Index n = c.cols();
  const Eigen::MatrixXd rigid = rigid_motion_basis(corners);
  // The singular values of C restricted to the complement of the rigid motions, ascending.
  Eigen::VectorXd sigma;
  Eigen::MatrixXd null_basis;  // candidates for the mechanisms, in the same order
  double largest = 0.0;
  if (n <= 2400) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(rigid);
    const Eigen::MatrixXd q = (qr.householderQ() * Eigen::MatrixXd::Identity(n, n)).rightCols(n - 6);
    const Eigen::MatrixXd reduced = c * q;  // sparse times dense: C has 6 to 12 entries a row
    const RightSingular svd = right_singular(reduced);
    const Eigen::VectorXd& s = svd.values;  // descending, min(rows, n - 6) of them
    largest = s.size() > 0 ? s(0) : 0.0;
    const Eigen::Index columns = n - 6;
    sigma = Eigen::VectorXd::Zero(columns);
    sigma.head(s.size()) = s;
    sigma.reverseInPlace();
    null_basis = q * svd.vectors.rowwise().reverse();
  } else {
    const Eigen::SparseMatrix<double> normal = c.transpose() * c;
    largest = std::sqrt(largest_eigenvalue(normal));
    std::size_t count = 8;
    for (;;) {
      const Eigenpairs pairs = smallest_eigenpairs(normal, rigid, count);
      sigma = pairs.values.cwiseMax(0.0).cwiseSqrt();
      null_basis = pairs.vectors;
      if (sigma(sigma.size() - 1) > 1e-6 * largest || count >= 64) break;
      count *= 2;
    }
  }
  const double line = (n <= 2400 ? mechanism_threshold : 1e-6) * largest;
  Eigen::Index zeros = 0;
  while (zeros < sigma.size() && sigma(zeros) <= line) ++zeros;
  m.internal_mechanisms = static_cast<std::size_t>(zeros);
  const std::size_t rank = static_cast<std::size_t>(n) - 6 - m.internal_mechanisms;
  m.self_stress_states = m.constraints - rank;
  for (Eigen::Index i = 0; i < std::min<Eigen::Index>(sigma.size(), zeros + 6); ++i) {
    m.singular_values.push_back(largest > 0.0 ? sigma(i) / largest : 0.0);
  }
  if (zeros > 0) m.largest_zero = m.singular_values[static_cast<std::size_t>(zeros - 1)];
  if (zeros < sigma.size()) m.smallest_nonzero = m.singular_values[static_cast<std::size_t>(zeros)];
  if (velocity) {
    const Eigen::VectorXd v = without_rigid_motions(velocity->head(n), rigid);
    const double norm = v.norm();
    if (norm > 0.0) {
      m.motion_residual = (c * v).norm() / (largest * norm);
      m.motion_in_mechanisms = zeros > 0 ? (null_basis.leftCols(zeros).transpose() * v).norm() / norm : 0.0;
    }
  }
  return m;
}

Mobility mobility(const Design& design, double t) {
  AssemblyConfiguration c;
  std::vector<Points> rates;
  const bool finite = design.assembly.evaluate_rate(t, c, rates);
  const ModelMesh mesh = model_mesh(design, c);
  std::optional<Eigen::VectorXd> velocity;
  if (finite) {
    Points v;
    mesh.nodes(rates, v);
    velocity = flatten(v);
  }
  return mobility(mesh, velocity);
}

nlohmann::json Mobility::to_json() const {
  return {{"corner_nodes", nodes},
          {"constraints", constraints},
          {"internal_mechanisms", internal_mechanisms},
          {"self_stress_states", self_stress_states},
          {"singular_values", singular_values},
          {"largest_zero", largest_zero},
          {"smallest_nonzero", smallest_nonzero},
          {"clear", clear()},
          {"motion_in_mechanisms", optional_json(motion_in_mechanisms)},
          {"motion_residual", optional_json(motion_residual)}};
}

std::ostream& operator<<(std::ostream& out, const Mobility& m) {
  out << "  mobility (rigid panels): " << m.internal_mechanisms << " internal mechanism"
      << (m.internal_mechanisms == 1 ? "" : "s") << ", " << m.self_stress_states << " states of self-stress";
  if (m.motion_in_mechanisms) {
    out << "; the motion lies in " << (m.internal_mechanisms == 1 ? "it" : "them") << " to "
        << format_human(*m.motion_in_mechanisms);
  }
  out << "\n    singular values over the largest: the mechanisms' at most " << format_human(m.largest_zero)
      << ", the next " << format_human(m.smallest_nonzero)
      << (m.clear() ? " (a clear gap)" : " (no clear gap: the count is uncertain)") << "\n";
  return out;
}

}  // namespace phedra
