#pragma once
// The inner loop of PHedron::evaluate (internal to generator/): one row of the
// motion in the user's frame, each vertex on its own (no vertex waits on the
// previous one), so that it runs at the speed of memory.

#include "phedra/vector_types.h"

#include <cstddef>
#include <vector>

namespace phedra {

/// What one row needs: the closed form of the rho recursion,
///   A_j = origin + alpha_j (first - origin) + b_j axis        (j = 0..count-1),
/// with alpha_0 = 1, b_0 = 0, alpha_{j+1} = alpha_j rho_j and
/// b_{j+1} = rho_j b_j + (1 - rho_j) s_{j+1} (NetMotion::row_alphas, row_offsets:
/// the same products in the same order, so the same numbers), and the general
/// net G_j = previous_j + q_j (A_j - axial_j). The two chains run inside the
/// vertex loop, so that their latency hides behind the vertices (a chain alone
/// before the loop cost as much as the loop). On exit `axial` holds A_j (it
/// held the previous row's) and `general` G_j.
struct RowArguments {
  const double* rho;    ///< NetMotion::row_ratios of the row
  const double* s;      ///< the apex heights at t (along the axis from the origin)
  const double* q;      ///< NetMotion::row_scales
  std::size_t count;
  Vec3 first;           ///< A_0 (the row's trajectory vertex), user frame
  Vec3 origin;          ///< the apex line's origin (s = 0), user frame
  Vec3 axis;            ///< its unit direction, user frame
  const Vec3* previous; ///< G of the previous row
  Vec3* general;        ///< G of this row (may be `previous`: advanced in place)
  Vec3* axial;          ///< A of the previous row in, of this row out
  /// Where the row also goes, with non-temporal stores (an output far larger than
  /// the caches; `general` is then a copy in the cache): the columns
  /// RowResult::streamed. nullptr: nowhere else.
  Vec3* stream_to = nullptr;
};

struct RowResult {
  Vec3 last_axial;  ///< A_{count-1}
  /// Columns [streamed_begin, streamed_end) were written to stream_to; the others
  /// are the caller's to stream (stream_row, in order, with the carry).
  std::size_t streamed_begin = 0, streamed_end = 0;
};

/// Computes the row. Uses AVX2 and FMA where the processor
/// has them (checked once), the portable loop elsewhere (and in WebAssembly).
RowResult advance_row(const RowArguments& row);

/// The portable loop (for the tests: both must agree to rounding).
RowResult advance_row_portable(const RowArguments& row);

/// When every row shares its ratios (NetMotion::uniform), alpha_j and b_j are the
/// same for all rows, so A_j - (A_j of the previous row) = alpha_j (first -
/// previous first), and a whole row of the output (the boundary columns too) is
/// the previous one plus a coefficient times delta: G_j = previous_j + c_j delta
/// (PHedron's row coefficients), with no axial row at all (and no cancellation
/// between two recursions).
struct UniformRowArguments {
  const double* c;      ///< the row's coefficients, `count` of them
  std::size_t count;
  Vec3 delta;           ///< A_0 of this row - A_0 of the previous row, user frame
  const Vec3* previous;
  Vec3* general;
};

void advance_uniform_row(const UniformRowArguments& row);
void advance_uniform_row_portable(const UniformRowArguments& row);

/// What a streamed output still owes: the doubles at the end of a row that do
/// not fill a 32-byte block, written together with the start of the next row.
struct StreamCarry {
  double pending[16];  ///< fewer than 4 between rows, and at most 9 (0..3 vertices) come at a time
  std::size_t count = 0;
  double* at = nullptr;  ///< where pending[0] goes
};

/// The same for an output far larger than the caches: the row is written to
/// `general` with non-temporal stores only (straight to memory: no read of the
/// output's lines before they are written, no eviction of what the loop reads;
/// a store of the ordinary kind into a line being streamed costs more than the
/// whole row) and to `copy`, which stays in the cache for the next row. `copy`
/// may overlap `row.previous` if it starts at or below it (StreamCopy). It
/// should lie as `general` does modulo 32 bytes (stores that straddle cache
/// lines cost about half the loop again). Consecutive rows must be contiguous
/// in memory. Call streaming_done() after the last row.
void advance_uniform_row_streaming(const UniformRowArguments& row, Vec3* copy, StreamCarry& carry);

/// The in-cache copy of the previous row for advance_uniform_row_streaming,
/// advanced in place (the smallest footprint in the cache) and kept at the
/// output row's address modulo 32 bytes: each row's copy starts 0..3 vertices
/// below the previous one (as the output rows lie), back at the top of a little
/// room once every dozens of rows.
class StreamCopy {
 public:
  explicit StreamCopy(std::size_t width) : room_(width + slack), width_(width) {}
  struct Place {
    const Vec3* previous;  ///< where the previous row's copy is
    Vec3* copy;            ///< where this row's goes (at or below `previous`)
  };
  /// The first row (a copy of `row`, which lies in the output).
  void start(const Vec3* row);
  /// The places for the next output row, which starts at `row`.
  Place next(const Vec3* row);
  const Vec3* last() const { return room_.data() + at_; }

 private:
  static constexpr std::size_t slack = 64;
  /// The highest place at or below `from` that lies as `row` does modulo 32 bytes (slack if none).
  std::size_t below(std::size_t from, const Vec3* row) const;
  std::vector<Vec3> room_;
  std::size_t width_, at_ = 0;
};
/// The first of room[0..3] that lies as `like` does modulo 32 bytes (room if none).
Vec3* place_like(Vec3* room, const Vec3* like);

/// Copies a row (computed in the cache) to an output far larger than the caches
/// with non-temporal stores only, as advance_uniform_row_streaming writes.
void stream_row(const Vec3* row, Vec3* out, std::size_t count, StreamCarry& carry);

/// Writes what `carry` still holds and orders the non-temporal stores before
/// anything the caller does next.
void streaming_done(StreamCarry& carry);

/// Whether an output of `bytes` is worth streaming (non-temporal stores, on a
/// processor that has them): larger than 32 MiB, more than the last-level cache
/// of one core on most processors, so that it would not stay in the cache anyway.
bool stream_output(std::size_t bytes);

/// For the tests: the output size from which stream_output is true (0: 32 MiB again).
void set_streaming_threshold(std::size_t bytes);

}  // namespace phedra
