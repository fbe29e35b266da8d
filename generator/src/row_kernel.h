#pragma once
// The inner loop of PHedron::evaluate (internal to generator/): one row of the
// motion in the user's frame, each vertex on its own (no vertex waits on the
// previous one), so that it runs at the speed of memory.

#include "phedra/vector_types.h"

#include <cstddef>

namespace phedra {

/// What one row needs: the closed form of the rho recursion,
///   A_j = origin + alpha_j (first - origin) + b_j axis        (j = 0..count-1),
/// and the general net G_j = previous_j + q_j (A_j - axial_j). On exit `axial`
/// holds A_j (it held the previous row's) and `general` G_j.
struct RowArguments {
  const double* alpha;  ///< NetMotion::row_alphas
  const double* b;      ///< NetMotion::row_offsets at t
  const double* q;      ///< NetMotion::row_scales
  std::size_t count;
  Vec3 first;           ///< A_0 (the row's trajectory vertex), user frame
  Vec3 origin;          ///< the apex line's origin (s = 0), user frame
  Vec3 axis;            ///< its unit direction, user frame
  const Vec3* previous; ///< G of the previous row
  Vec3* general;        ///< G of this row (may not alias `previous`)
  Vec3* axial;          ///< A of the previous row in, of this row out
};

/// Computes the row; returns A_{count-1}. Uses AVX2 and FMA where the processor
/// has them (checked once), the portable loop elsewhere (and in WebAssembly).
Vec3 advance_row(const RowArguments& row);

/// The portable loop (for the tests: both must agree to rounding).
Vec3 advance_row_portable(const RowArguments& row);

/// When every row shares its ratios (NetMotion::uniform), alpha_j and b_j are the
/// same for all rows, so A_j - (A_j of the previous row) = alpha_j (first -
/// previous first): G_j = previous_j + q_j alpha_j delta, with no axial row at
/// all (and no cancellation between two recursions).
struct UniformRowArguments {
  const double* alpha;  ///< NetMotion::row_alphas (shared)
  const double* q;      ///< NetMotion::row_scales of the row
  std::size_t count;
  Vec3 delta;           ///< A_0 of this row - A_0 of the previous row, user frame
  const Vec3* previous;
  Vec3* general;
};

void advance_uniform_row(const UniformRowArguments& row);
void advance_uniform_row_portable(const UniformRowArguments& row);

}  // namespace phedra
