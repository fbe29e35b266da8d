#pragma once
// The fold angles and their rates in bulk, for the energy landscape (internal to
// mechanics/): plain arrays, the angles' atan2 four at a time (glibc's libmvec,
// AVX2) where the processor has it.
//
// MERLIN2's angle from the panels' unit normals. The model's panels are planar
// at every t (the motion is exact), so a fold's m = r_ij x r_kj is its first
// panel's normal n_A times a positive length and a sign fixed by the panel's
// corner order, and n = r_kj x r_kl likewise n_B: with e = r_kj / |r_kj|,
//   theta = atan2((m x n) . e, m . n) = atan2(e . (n_A x s n_B), n_A . s n_B),
// s = +-1 the fold's product of the two signs (taken at the model's t). The
// panels turn rigidly, so d theta / dt = (w_B - w_A) . e, w a panel's angular
// velocity (X dY/dt - Y dX/dt for a turn of B about e is the turn itself); its
// part along the panel's normal is across e, so n x dn/dt (the rest of w) is
// enough. A panel's normal and that turn come once a panel from its diagonals
// (a triangle: two sides), not twice a fold; no n5b8 centre is needed.
//
// The energy's pass (energy()) runs over the folds in blocks of 256: a block's
// angles, their atan2, the continuity and the energy's sums while the block is
// in the first cache level, and no whole-array scratch. One sample's kernel is
// bound by its arithmetic and scalar loads (about 13 cycles a fold), so the
// landscape runs four samples at once (energy_lanes): their numbers side by
// side, one AVX2 instruction doing a step of all four (docs/performance.md).

#include "phedra/bar_hinge_model.h"

#include <cstdint>
#include <vector>

namespace phedra {

class FoldKernel {
 public:
  explicit FoldKernel(const BarHingeModel& model);
  std::size_t size() const { return j_.size(); }

  /// theta of every fold at the corner nodes' positions, in (-pi, pi] (hinge_angle's
  /// value up to 2 pi), and (rates not null) d theta / dt for the corner nodes'
  /// rates. `frames` is scratch of any size.
  void angles(const Points& corners, const Points* rates, double* theta, double* rate, std::vector<double>& frames) const;

  struct Sums {
    double energy = 0.0;   ///< sum of 1/2 w (theta - rest)^2
    double rate = 0.0;     ///< sum of w (theta - rest) d theta / dt (with rates; 0 without)
    double largest = 0.0;  ///< the largest |theta - reference| (0 with given turns)
  };
  /// Each fold's angle made continuous: theta + 2 pi turns, turns the whole number
  /// that brings it nearest `reference` (or, `reference` null, the given `turns`),
  /// into `angles` and `turns`; and the sums of the fold springs' energy (rest
  /// angles `rest`, weights `weight`: k L) and its rate (rates not null).
  Sums energy(const Points& corners, const Points* rates, const double* reference, const double* rest,
              const double* weight, double* angles, std::int8_t* turns, std::vector<double>& frames) const;

  /// Samples evaluated together (SIMD across samples, no gathers: each number a
  /// kernel loads is the lanes' four in a row).
  static constexpr std::size_t lanes = 4;
  /// energy() of `lanes` samples at once, each lane the same bits as energy() of
  /// it alone: the corner nodes' positions `p` and rates `v` interleaved,
  /// [node][coordinate][lane]; lane l's angles continuous from lane l - 1's
  /// (lane 0's from `reference`, not null) into angles[l], turns[l], sums[l].
  void energy_lanes(const double* p, const double* v, const double* reference, const double* rest,
                    const double* weight, double* const* angles, std::int8_t* const* turns, Sums* sums,
                    std::vector<double>& frames) const;

 private:
  /// The panels' unit normals and turns into `frames` (6 numbers a panel, each a
  /// lane: [panel][number][lane]) from the nodes' positions `p` and rates `v`
  /// (null: none), [node][coordinate][lane].
  template <std::size_t L>
  void panel_frames(const double* p, const double* v, double* frames) const;
  /// Folds h0 .. h0 + count - 1 of L samples: theta (y, x and, L > 1, `turned`:
  /// scratch of L * stride), and with rates the rates; lane l's fold i at [l * stride + i].
  template <std::size_t L>
  void block(std::size_t h0, std::size_t count, const double* p, bool rates, const double* frames, double* theta,
             double* rate, double* y, double* x, double* turned, std::size_t stride) const;
  template <std::size_t L>
  void energy(const double* p, const double* v, const double* reference, const double* rest, const double* weight,
              double* const* angles, std::int8_t* const* turns, Sums* sums, double* frames) const;

  /// Each panel's normal is (P[c] - P[a]) x (P[d] - P[b]).
  std::vector<std::uint32_t> panel_a_, panel_b_, panel_c_, panel_d_;
  /// 1 / |(P[c] - P[a]) x (P[d] - P[b])|: the motion keeps it (the panel is rigid).
  std::vector<double> inverse_normal_;
  std::vector<std::uint32_t> j_, k_, first_, second_;  ///< the hinge's edge j-k and its two panels
  std::vector<double> signed_inverse_length_;          ///< s / |r_kj| (the motion keeps the length)
};

}  // namespace phedra
