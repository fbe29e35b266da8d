#include "row_kernel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__EMSCRIPTEN__)
#define PHEDRA_ROW_AVX2 1
#include <immintrin.h>
#endif

namespace phedra {

namespace {

/// alpha_j and b_j of the row being advanced.
struct RowChain {
  double alpha = 1.0, b = 0.0;
  /// From column j to j + 1.
  void step(const RowArguments& r, std::size_t j) {
    const double rho = r.rho[j];
    b = rho * b + (1.0 - rho) * r.s[j + 1];
    alpha *= rho;
  }
};

/// Columns from..to-1 of the row, the chain at column `from` (at `to` on exit).
void advance_row_range(const RowArguments& r, std::size_t from, std::size_t to, RowChain& chain) {
  const double dx = r.first.x() - r.origin.x(), dy = r.first.y() - r.origin.y(), dz = r.first.z() - r.origin.z();
  double* a = r.axial->data();
  double* g = r.general->data();  // may be `p` (in place: each element read before it is written)
  const double* p = r.previous->data();
  for (std::size_t j = from; j < to; ++j) {
    const double al = chain.alpha, b = chain.b, q = r.q[j];
    if (j + 1 < r.count) chain.step(r, j);
    const double x = r.origin.x() + al * dx + b * r.axis.x();
    const double y = r.origin.y() + al * dy + b * r.axis.y();
    const double z = r.origin.z() + al * dz + b * r.axis.z();
    g[3 * j] = p[3 * j] + q * (x - a[3 * j]);
    g[3 * j + 1] = p[3 * j + 1] + q * (y - a[3 * j + 1]);
    g[3 * j + 2] = p[3 * j + 2] + q * (z - a[3 * j + 2]);
    a[3 * j] = x;
    a[3 * j + 1] = y;
    a[3 * j + 2] = z;
  }
}

}  // namespace

RowResult advance_row_portable(const RowArguments& r) {
  RowChain chain;
  advance_row_range(r, 0, r.count, chain);
  return {r.count ? r.axial[r.count - 1] : r.first, 0, 0};
}

void advance_uniform_row_portable(const UniformRowArguments& r) {
  const double dx = r.delta.x(), dy = r.delta.y(), dz = r.delta.z();
  double* __restrict g = r.general->data();
  const double* __restrict p = r.previous->data();
  for (std::size_t j = 0; j < r.count; ++j) {
    const double c = r.c[j];
    g[3 * j] = p[3 * j] + c * dx;
    g[3 * j + 1] = p[3 * j + 1] + c * dy;
    g[3 * j + 2] = p[3 * j + 2] + c * dz;
  }
}

namespace {

/// The portable streaming loop: the same numbers into both rows.
void advance_uniform_row_both(const UniformRowArguments& r, Vec3* copy) {
  for (std::size_t j = 0; j < r.count; ++j) {
    const Vec3 v = r.previous[j] + r.c[j] * r.delta;
    copy[j] = v;
    r.general[j] = v;
  }
}

std::size_t& streaming_threshold() {
  static std::size_t bytes = 0;
  return bytes;
}

/// Outputs larger than this are streamed: more than the last-level cache one
/// core has on most processors (the C library's figure is the whole package's
/// on some: 320 MiB reported on a virtual machine whose core sees 32 MiB).
constexpr std::size_t default_streaming_threshold = std::size_t{32} << 20;

}  // namespace

#ifdef PHEDRA_ROW_AVX2
namespace {

/// Patterns of a vector (x, y, z) over 4 interleaved vertices: (x y z x) (y z x y) (z x y z).
struct Patterns {
  __m256d k[3];
  __attribute__((target("avx2,fma"))) explicit Patterns(const Vec3& d)
      : k{_mm256_setr_pd(d.x(), d.y(), d.z(), d.x()), _mm256_setr_pd(d.y(), d.z(), d.x(), d.y()),
          _mm256_setr_pd(d.z(), d.x(), d.y(), d.z())} {}
};

/// Four per-vertex numbers spread over the three vectors of their interleaved
/// x y z: (v0 v0 v0 v1) (v1 v1 v2 v2) (v2 v3 v3 v3).
struct Spread {
  __m256d k[3];
  __attribute__((target("avx2,fma"))) explicit Spread(__m256d v)
      : k{_mm256_permute4x64_pd(v, 0x40), _mm256_permute4x64_pd(v, 0xA5), _mm256_permute4x64_pd(v, 0xFE)} {}
};

/// One vertex as a lane of the vector loops computes it (one rounding a coordinate).
__attribute__((target("avx2,fma"))) inline Vec3 fused_step(const Vec3& p, double c, const Vec3& d) {
  return Vec3(std::fma(c, d.x(), p.x()), std::fma(c, d.y(), p.y()), std::fma(c, d.z(), p.z()));
}

__attribute__((target("avx2,fma"))) void advance_uniform_row_avx2(const UniformRowArguments& r) {
  const Patterns dp(r.delta);
  double* g = r.general->data();
  const double* p = r.previous->data();
  std::size_t j = 0;
  for (; j + 4 <= r.count; j += 4) {
    const Spread c(_mm256_loadu_pd(r.c + j));
    double* gj = g + 3 * j;
    const double* pj = p + 3 * j;
    for (int k = 0; k < 3; ++k) _mm256_storeu_pd(gj + 4 * k, _mm256_fmadd_pd(c.k[k], dp.k[k], _mm256_loadu_pd(pj + 4 * k)));
  }
  for (; j < r.count; ++j) r.general[j] = fused_step(r.previous[j], r.c[j], r.delta);  // the last 0..3 vertices
}

/// Appends doubles to the carry and streams its whole 32-byte blocks; what comes
/// before the first block boundary (only at the start of the output, or after a
/// gap: the carry's end is not `at`) is written the ordinary way. The carry then
/// holds fewer than 4 doubles.
__attribute__((target("avx2,fma"))) void carry_out(StreamCarry& carry, double* at, const double* values,
                                                   std::size_t count) {
  if (carry.count && carry.at + carry.count != at) {
    std::copy(carry.pending, carry.pending + carry.count, carry.at);
    carry.count = 0;
  }
  if (!carry.count) carry.at = at;
  std::copy(values, values + count, carry.pending + carry.count);
  carry.count += count;
  std::size_t k = 0;
  for (; k < carry.count && reinterpret_cast<std::uintptr_t>(carry.at + k) % 32 != 0; ++k) carry.at[k] = carry.pending[k];
  for (; k + 4 <= carry.count; k += 4) _mm256_stream_pd(carry.at + k, _mm256_loadu_pd(carry.pending + k));
  std::copy(carry.pending + k, carry.pending + carry.count, carry.pending);
  carry.at += k;
  carry.count -= k;
}

/// Streaming: groups of four vertices (96 bytes, three 32-byte blocks) from the
/// first vertex whose output address starts a block; the 0..3 vertices before
/// it and after the last group go through the carry, joined with the previous
/// and the next row into whole blocks.
__attribute__((target("avx2,fma"))) void advance_uniform_row_streaming_avx2(const UniformRowArguments& r,
                                                                           Vec3* copy, StreamCarry& carry) {
  std::size_t head = 0;
  while (head < 4 && head < r.count && reinterpret_cast<std::uintptr_t>(r.general + head) % 32 != 0) ++head;
  if (head == 4) {  // an output not even 8-byte aligned: the ordinary way
    streaming_done(carry);
    return advance_uniform_row_both(r, copy);
  }
  auto one_by_one = [&](std::size_t from, std::size_t to) {
    for (std::size_t j = from; j < to; ++j) copy[j] = fused_step(r.previous[j], r.c[j], r.delta);
    if (to > from) carry_out(carry, r.general[from].data(), copy[from].data(), 3 * (to - from));
  };
  one_by_one(0, std::min(head, r.count));
  const Patterns dp(r.delta);
  const double* const c = r.c;
  const double* const p = r.previous->data();
  double* const g = r.general->data();
  double* const s = copy->data();
  std::size_t j = head;
  for (; j + 4 <= r.count; j += 4) {
    const Spread cj(_mm256_loadu_pd(c + j));
    for (int k = 0; k < 3; ++k) {
      const std::size_t at = 3 * j + 4 * k;
      const __m256d v = _mm256_fmadd_pd(cj.k[k], dp.k[k], _mm256_loadu_pd(p + at));
      _mm256_storeu_pd(s + at, v);
      _mm256_stream_pd(g + at, v);
    }
  }
  one_by_one(j, r.count);
}

__attribute__((target("avx2,fma"))) void stream_row_avx2(const Vec3* row, Vec3* out, std::size_t count,
                                                         StreamCarry& carry) {
  double* to = out->data();
  const double* from = row->data();
  const std::size_t doubles = 3 * count;
  std::size_t head = 0;
  while (head < doubles && head < 4 && reinterpret_cast<std::uintptr_t>(to + head) % 32 != 0) ++head;
  if (head == 4) {  // not 8-byte aligned: the ordinary way
    streaming_done(carry);
    std::copy(from, from + doubles, to);
    return;
  }
  carry_out(carry, to, from, head);
  std::size_t k = head;
  for (; k + 4 <= doubles; k += 4) _mm256_stream_pd(to + k, _mm256_loadu_pd(from + k));
  carry_out(carry, to + k, from + k, doubles - k);
}

/// Four vertices at a time as three vectors of the interleaved x y z: the
/// per-vertex numbers (alpha, b, q) spread over them by lane permutes, the
/// per-row vectors (first - origin, origin, axis) as the same three patterns.
__attribute__((target("avx2,fma"))) RowResult advance_row_avx2(const RowArguments& r) {
  const Patterns dp(r.first - r.origin), op(r.origin), ap(r.axis);
  double* const a = r.axial->data();
  double* const g = r.general->data();
  const double* const p = r.previous->data();
  const double* const rho = r.rho;
  const double* const s = r.s;
  const double* const q = r.q;
  const std::size_t count = r.count;
  double* const out = r.stream_to ? r.stream_to->data() : nullptr;
  // Streaming: the groups start where the output does on a 32-byte block.
  std::size_t begin = 0;
  while (out && begin < 4 && reinterpret_cast<std::uintptr_t>(out + 3 * begin) % 32 != 0) ++begin;
  if (begin == 4) begin = count;  // an output not 8-byte aligned: no groups
  const std::size_t first = std::min(begin, count);
  RowChain chain;
  advance_row_range(r, 0, first, chain);
  std::size_t j = first;
  for (; j + 4 <= count; j += 4) {
    double al[4], b[4];
    for (std::size_t k = 0; k < 4; ++k) {
      al[k] = chain.alpha;
      b[k] = chain.b;
      if (j + k + 1 < count) {
        // b's chain is one fused multiply-add a vertex (4 cycles); as the compiler
        // contracts the plain expression, rho b was a multiply before it (7).
        const double rh = rho[j + k];
        chain.b = std::fma(rh, chain.b, (1.0 - rh) * s[j + k + 1]);
        chain.alpha *= rh;
      }
    }
    const Spread alk(_mm256_setr_pd(al[0], al[1], al[2], al[3])), bk(_mm256_setr_pd(b[0], b[1], b[2], b[3])),
        qk(_mm256_loadu_pd(q + j));
    for (int k = 0; k < 3; ++k) {
      const std::size_t at = 3 * j + 4 * k;
      const __m256d axial = _mm256_fmadd_pd(bk.k[k], ap.k[k], _mm256_fmadd_pd(alk.k[k], dp.k[k], op.k[k]));
      const __m256d v = _mm256_fmadd_pd(qk.k[k], _mm256_sub_pd(axial, _mm256_loadu_pd(a + at)), _mm256_loadu_pd(p + at));
      _mm256_storeu_pd(g + at, v);
      if (out) _mm256_stream_pd(out + at, v);
      _mm256_storeu_pd(a + at, axial);
    }
  }
  advance_row_range(r, j, count, chain);
  return {count ? r.axial[count - 1] : r.first, out ? first : 0, out ? j : 0};
}

bool has_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
}

}  // namespace
#endif

void advance_uniform_row(const UniformRowArguments& r) {
#ifdef PHEDRA_ROW_AVX2
  if (has_avx2()) return advance_uniform_row_avx2(r);
#endif
  advance_uniform_row_portable(r);
}

void advance_uniform_row_streaming(const UniformRowArguments& r, Vec3* copy, StreamCarry& carry) {
#ifdef PHEDRA_ROW_AVX2
  if (has_avx2()) return advance_uniform_row_streaming_avx2(r, copy, carry);
#endif
  advance_uniform_row_both(r, copy);
}

Vec3* place_like(Vec3* room, const Vec3* like) {
  for (std::size_t k = 0; k < 4; ++k) {
    if (reinterpret_cast<std::uintptr_t>(room + k) % 32 == reinterpret_cast<std::uintptr_t>(like) % 32) return room + k;
  }
  return room;
}

std::size_t StreamCopy::below(std::size_t from, const Vec3* row) const {
  const auto target = reinterpret_cast<std::uintptr_t>(row) % 32;
  for (std::size_t k = 0; k < 4 && k <= from; ++k) {
    if (reinterpret_cast<std::uintptr_t>(room_.data() + (from - k)) % 32 == target) return from - k;
  }
  return slack;
}

void StreamCopy::start(const Vec3* row) {
  at_ = below(slack - 1, row);
  if (at_ == slack) at_ = slack - 1;  // an output not 8-byte aligned (streamed the ordinary way)
  std::memcpy(room_[at_].data(), row->data(), width_ * sizeof(Vec3));
}

StreamCopy::Place StreamCopy::next(const Vec3* row) {
  std::size_t to = below(at_, row);
  if (to == slack) {  // at the bottom of the room: the copy goes back to the top
    const std::size_t top = slack - 1;
    std::memmove(room_[top].data(), room_[at_].data(), width_ * sizeof(Vec3));
    at_ = top;
    to = below(top, row);
    if (to == slack) to = top;
  }
  const Place place{room_.data() + at_, room_.data() + to};
  at_ = to;
  return place;
}

void stream_row(const Vec3* row, Vec3* out, std::size_t count, StreamCarry& carry) {
#ifdef PHEDRA_ROW_AVX2
  if (has_avx2()) return stream_row_avx2(row, out, count, carry);
#endif
  std::copy(row, row + count, out);
}

void streaming_done(StreamCarry& carry) {
  std::copy(carry.pending, carry.pending + carry.count, carry.at);
  carry.count = 0;
#ifdef PHEDRA_ROW_AVX2
  _mm_sfence();
#endif
}

bool stream_output(std::size_t bytes) {
#ifdef PHEDRA_ROW_AVX2
  const std::size_t threshold = streaming_threshold() ? streaming_threshold() : default_streaming_threshold;
  return has_avx2() && bytes > threshold;
#else
  (void)bytes;
  return false;
#endif
}

void set_streaming_threshold(std::size_t bytes) { streaming_threshold() = bytes; }

RowResult advance_row(const RowArguments& r) {
#ifdef PHEDRA_ROW_AVX2
  if (has_avx2()) return advance_row_avx2(r);
#endif
  return advance_row_portable(r);
}

}  // namespace phedra
