#pragma once
// The per-row recursions of the motion (MATH.md sections 3 and 4), shared by a
// P-hedron and by the members of an assembly: once column 0 of the axial net
// and the first two apexes are known at t, everything else follows from
// constants fixed at t*.

#include "phedra/axial_net.h"
#include "phedra/parallel_net.h"

#include <functional>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace phedra {

/// The motion state of one net at one t, canonical frame (or its rate d/dt:
/// every recursion after column 0 is linear, so the rates follow the same ones).
struct NetState {
  Points axial;                 ///< rows x n, row-major
  Points general;               ///< rows x n
  std::vector<double> apexes;   ///< s_0..s_n
};

class NetMotion {
 public:
  NetMotion() = default;
  /// Constants from the axial and parallel nets at t*.
  NetMotion(const AxialNet& axial, const ParallelNet& parallel, const std::vector<Sign>& signs);

  /// Sees row i of the axial and of the general net at t* (n entries each, canonical frame).
  using RowSink = std::function<void(std::size_t i, const Vec3* axial, const Vec3* general)>;
  /// Builds both nets row by row (build_axial_row, build_parallel_row) and keeps
  /// only the constants: memory is O(n) besides them. `column` is step 1 of the
  /// axial net, `trajectory` the general net's column 0.
  NetMotion(const CanonicalInput& input, const AxialColumn& column, const Points& trajectory, const RowSink& sink);

  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return columns_; }

  /// rho_{i,0..n-2} and the transversal scales q_{i,0..n-1} of row i.
  const double* row_ratios(std::size_t i) const { return &ratios_[i * ratio_stride_]; }
  /// alpha_{i,0..n-1}: alpha_{i,0} = 1, alpha_{i,j+1} = alpha_{i,j} rho_{i,j}. The rho
  /// recursion in closed form: A[i][j] = S-line point + alpha_{i,j} (A[i][0] - origin) +
  /// b_{i,j}(t) axis (row_offsets), so a row's vertices do not wait on each other.
  const double* row_alphas(std::size_t i) const { return &alphas_[i * (ratio_stride_ == 0 ? 0 : columns_)]; }
  /// Whether every row shares its ratios (every sign '+'): row_alphas and the
  /// offsets are then the same for all rows.
  bool uniform() const { return ratio_stride_ == 0; }
  /// b_{i,0..n-1} of row i at the apex heights s[0..n] (along the axis from the
  /// origin): b_{i,0} = 0, b_{i,j+1} = rho_{i,j} b_{i,j} + (1 - rho_{i,j}) s[j+1].
  void row_offsets(std::size_t i, const double* s, double* b) const {
    const double* rho = row_ratios(i);
    b[0] = 0.0;
    for (std::size_t j = 0; j + 1 < columns_; ++j) b[j + 1] = rho[j] * b[j] + (1.0 - rho[j]) * s[j + 1];
  }
  const double* row_scales(std::size_t i) const { return &scales_[i * columns_]; }
  /// +1 for a '+' sign, -1 for '-' (M+/M- on z): n - 1 entries (complete_first_row).
  const double* mirrors() const { return mirror_.data(); }

  /// The L_0 recursion: apexes s[0..n] and row 0 of the axial net at t, from
  /// s[0], s[1] and the row's first vertex (in the plane pi_0). Linear in its
  /// arguments (as fill_row and advance_general_row are): applied to their rates
  /// d/dt it gives the rates.
  void complete_first_row(double s0, double s1, const Vec3& first, double* s, Vec3* row) const;

  /// Row i of the axial net from row[0] and the apexes: A[i][j+1] = S_{j+1} + rho (A[i][j] - S_{j+1}),
  /// columns 1 .. count - 1 (count at most n: all of them).
  void fill_row(std::size_t i, const double* s, Vec3* row, std::size_t count = SIZE_MAX) const {
    const double* rho = row_ratios(i);
    const std::size_t end = std::min(count, columns_);
    for (std::size_t j = 0; j + 1 < end; ++j) {
      const double c = s[j + 1];
      const Vec3& a = row[j];
      row[j + 1] = Vec3(rho[j] * a.x(), rho[j] * a.y(), c + rho[j] * (a.z() - c));
    }
  }

  /// Row i (>= 1) of the general net: G[i][j] = G[i-1][j] + q_{i,j} (A[i][j] - A[i-1][j]),
  /// for columns first .. count - 1 (first = 1 when column 0 is given; count at most n).
  void advance_general_row(std::size_t i, const Vec3* previous_axial, const Vec3* axial, const Vec3* previous_general,
                           Vec3* general, std::size_t first = 0, std::size_t count = SIZE_MAX) const {
    const double* q = &scales_[i * columns_];
    const std::size_t end = std::min(count, columns_);
    for (std::size_t j = first; j < end; ++j) {
      general[j] = previous_general[j] + q[j] * (axial[j] - previous_axial[j]);
    }
  }

 private:
  std::size_t rows_ = 0, columns_ = 0;
  /// rho_{i,j}, rows x (n - 1); a single row when every sign is '+' (a sigma+
  /// ratio depends on the apex heights alone, not on the row), stride 0 then.
  std::vector<double> ratios_;
  std::size_t ratio_stride_ = 0;
  std::vector<double> alphas_;  ///< products of the ratios, rows (or 1) x n
  void compute_alphas();
  std::vector<double> scales_;  ///< parallel-net transversal scale factors, rows x n
  std::vector<double> mirror_;  ///< +1 for '+', -1 for '-' (M+/M- on z), n - 1
};

}  // namespace phedra
