#include "supernodal_solve.h"

#include "lane4.h"
#include "phedra/cpu_clones.h"

#include <cstddef>
#include <cstring>

namespace phedra {
namespace {

/// Supernode s of l: its first column, its column count, its rows below them,
/// its values (column-major, leading dimension ld) and those rows' indices.
struct Supernode {
  int first, columns, below;
  std::size_t ld;
  const double* values;
  const int* below_rows;
};
[[gnu::always_inline]] inline Supernode supernode(const SupernodalFactor& l, int s) {
  const int first = l.super[s], columns = l.super[s + 1] - first;
  const int height = l.row_start[s + 1] - l.row_start[s];
  return {first, columns, height - columns, static_cast<std::size_t>(height), l.values + l.value_start[s],
          l.rows + l.row_start[s] + columns};
}

/// y[0..n) -= sum over k < w of column k (entries c + k ld ..) times x[k]; w <= 4.
[[gnu::always_inline]] inline void subtract_columns(double* y, int n, const double* c, std::size_t ld, const double* x,
                                                    int w) {
  int i = 0;
  if (w == 4) {
    const double x0 = x[0], x1 = x[1], x2 = x[2], x3 = x[3];
    const double *c0 = c, *c1 = c + ld, *c2 = c + 2 * ld, *c3 = c + 3 * ld;
    for (; i + 4 <= n; i += 4) {
      store4(y + i, load4(y + i) - (load4(c0 + i) * x0 + load4(c1 + i) * x1 + load4(c2 + i) * x2 + load4(c3 + i) * x3));
    }
    for (; i < n; ++i) y[i] -= c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
    return;
  }
  for (int k = 0; k < w; ++k) {
    const double* ck = c + static_cast<std::size_t>(k) * ld;
    const double xk = x[k];
    for (i = 0; i + 4 <= n; i += 4) store4(y + i, load4(y + i) - load4(ck + i) * xk);
    for (; i < n; ++i) y[i] -= ck[i] * xk;
  }
}

/// r[k] += column k (entries c + k ld ..) . v[0..n), for k < w; w <= 4.
[[gnu::always_inline]] inline void add_dots(double* r, int n, const double* c, std::size_t ld, const double* v, int w) {
  int i = 0;
  if (w == 4) {
    const double *c0 = c, *c1 = c + ld, *c2 = c + 2 * ld, *c3 = c + 3 * ld;
    Lane4 s0 = {0.0, 0.0, 0.0, 0.0}, s1 = s0, s2 = s0, s3 = s0;
    for (; i + 4 <= n; i += 4) {
      const Lane4 t = load4(v + i);
      s0 += load4(c0 + i) * t;
      s1 += load4(c1 + i) * t;
      s2 += load4(c2 + i) * t;
      s3 += load4(c3 + i) * t;
    }
    double r0 = sum4(s0), r1 = sum4(s1), r2 = sum4(s2), r3 = sum4(s3);
    for (; i < n; ++i) {
      r0 += c0[i] * v[i];
      r1 += c1[i] * v[i];
      r2 += c2[i] * v[i];
      r3 += c3[i] * v[i];
    }
    r[0] += r0;
    r[1] += r1;
    r[2] += r2;
    r[3] += r3;
    return;
  }
  for (int k = 0; k < w; ++k) {
    const double* ck = c + static_cast<std::size_t>(k) * ld;
    Lane4 s = {0.0, 0.0, 0.0, 0.0};
    for (i = 0; i + 4 <= n; i += 4) s += load4(ck + i) * load4(v + i);
    double rk = sum4(s);
    for (; i < n; ++i) rk += ck[i] * v[i];
    r[k] += rk;
  }
}

}  // namespace

PHEDRA_CPU_CLONES void supernodal_solve(const SupernodalFactor& l, double* x, double* work) {
  // L y = x: each supernode's columns in blocks of four: the block's triangle,
  // then the rows below it (the supernode's own, then its rectangle into work,
  // scattered to x at the end).
  for (int s = 0; s < l.supernodes; ++s) {
    const auto [first, columns, below, ld, a, rows] = supernode(l, s);
    double* xs = x + first;
    for (int i = 0; i < below; ++i) work[i] = 0.0;
    for (int jb = 0; jb < columns; jb += 4) {
      const int w = columns - jb < 4 ? columns - jb : 4;
      const double* block = a + static_cast<std::size_t>(jb) * ld;
      for (int j = 0; j < w; ++j) {
        const double* column = block + static_cast<std::size_t>(j) * ld;
        const double xj = xs[jb + j] /= column[jb + j];
        for (int i = j + 1; i < w; ++i) xs[jb + i] -= column[jb + i] * xj;
      }
      subtract_columns(xs + jb + w, columns - jb - w, block + jb + w, ld, xs + jb, w);
      subtract_columns(work, below, block + columns, ld, xs + jb, w);
    }
    for (int i = 0; i < below; ++i) x[rows[i]] += work[i];  // work holds minus the products
  }
  // L^T x = y: the supernodes in reverse, each block of four columns from the last.
  for (int s = l.supernodes - 1; s >= 0; --s) {
    const auto [first, columns, below, ld, a, rows] = supernode(l, s);
    double* xs = x + first;
    for (int i = 0; i < below; ++i) work[i] = x[rows[i]];
    for (int jb = (columns - 1) / 4 * 4; jb >= 0; jb -= 4) {
      const int w = columns - jb < 4 ? columns - jb : 4;
      const double* block = a + static_cast<std::size_t>(jb) * ld;
      double r[4] = {0.0, 0.0, 0.0, 0.0};
      add_dots(r, below, block + columns, ld, work, w);
      add_dots(r, columns - jb - w, block + jb + w, ld, xs + jb + w, w);
      for (int j = w - 1; j >= 0; --j) {
        const double* column = block + static_cast<std::size_t>(j) * ld;
        double sum = r[j];
        for (int i = j + 1; i < w; ++i) sum += column[jb + i] * xs[jb + i];
        xs[jb + j] = (xs[jb + j] - sum) / column[jb + j];
      }
    }
  }
}

namespace {

/// y[i] -= sum over k < w of column k's entry i times x[k], for i < n: rows of four
/// right-hand sides (y and x interleaved, Lane4 a row).
[[gnu::always_inline]] inline void subtract_columns4(double* y, int n, const double* c, std::size_t ld, const double* x,
                                                     int w) {
  const Lane4 x0 = load4(x), x1 = w > 1 ? load4(x + 4) : Lane4{}, x2 = w > 2 ? load4(x + 8) : Lane4{},
              x3 = w > 3 ? load4(x + 12) : Lane4{};
  const double *c0 = c, *c1 = c + ld, *c2 = c + 2 * ld, *c3 = c + 3 * ld;
  if (w == 4) {
    for (int i = 0; i < n; ++i) store4(y + 4 * i, load4(y + 4 * i) - (c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3));
    return;
  }
  for (int i = 0; i < n; ++i) {
    Lane4 sum = c0[i] * x0;
    if (w > 1) sum += c1[i] * x1;
    if (w > 2) sum += c2[i] * x2;
    store4(y + 4 * i, load4(y + 4 * i) - sum);
  }
}

/// r[k] += sum over i < n of column k's entry i times v[i] (rows of four), for k < w.
[[gnu::always_inline]] inline void add_dots4(Lane4* r, int n, const double* c, std::size_t ld, const double* v, int w) {
  const double *c0 = c, *c1 = c + ld, *c2 = c + 2 * ld, *c3 = c + 3 * ld;
  Lane4 s0 = {0.0, 0.0, 0.0, 0.0}, s1 = s0, s2 = s0, s3 = s0;
  if (w == 4) {
    // Two rows an iteration into two sets of sums: eight independent chains of
    // multiply-adds (four would wait on the adds' latency).
    Lane4 u0 = s0, u1 = s0, u2 = s0, u3 = s0;
    int i = 0;
    for (; i + 2 <= n; i += 2) {
      const Lane4 t = load4(v + 4 * i), t1 = load4(v + 4 * i + 4);
      s0 += c0[i] * t;
      s1 += c1[i] * t;
      s2 += c2[i] * t;
      s3 += c3[i] * t;
      u0 += c0[i + 1] * t1;
      u1 += c1[i + 1] * t1;
      u2 += c2[i + 1] * t1;
      u3 += c3[i + 1] * t1;
    }
    if (i < n) {
      const Lane4 t = load4(v + 4 * i);
      s0 += c0[i] * t;
      s1 += c1[i] * t;
      s2 += c2[i] * t;
      s3 += c3[i] * t;
    }
    s0 += u0;
    s1 += u1;
    s2 += u2;
    s3 += u3;
  } else {
    for (int i = 0; i < n; ++i) {
      const Lane4 t = load4(v + 4 * i);
      s0 += c0[i] * t;
      if (w > 1) s1 += c1[i] * t;
      if (w > 2) s2 += c2[i] * t;
    }
  }
  r[0] += s0;
  r[1] += s1;
  r[2] += s2;
  r[3] += s3;
}

/// Asks for the factor's entries `ahead` rows beyond row i of eight columns, for
/// the non-temporal level (each entry is read once a pass): the eight streams of
/// a block otherwise wait on memory at every block's start (docs/performance.md).
[[gnu::always_inline]] inline void prefetch_columns8(const double* c, std::size_t ld, int i) {
  constexpr int ahead = 48;  // rows: six cache lines
  for (std::size_t k = 0; k < 8; ++k) __builtin_prefetch(c + k * ld + i + ahead, 0, 0);
}

/// subtract_columns4 for eight columns: y's row read and written once for eight
/// of the factor's entries (the pass's traffic to y halved), the sum a tree.
[[gnu::always_inline]] inline void subtract_columns8(double* y, int n, const double* c, std::size_t ld, const double* x) {
  const Lane4 x0 = load4(x), x1 = load4(x + 4), x2 = load4(x + 8), x3 = load4(x + 12), x4 = load4(x + 16),
              x5 = load4(x + 20), x6 = load4(x + 24), x7 = load4(x + 28);
  const double *c0 = c, *c1 = c + ld, *c2 = c + 2 * ld, *c3 = c + 3 * ld, *c4 = c + 4 * ld, *c5 = c + 5 * ld,
               *c6 = c + 6 * ld, *c7 = c + 7 * ld;
  for (int i = 0; i < n; ++i) {
    if ((i & 7) == 0) prefetch_columns8(c, ld, i);
    const Lane4 s = c0[i] * x0 + c1[i] * x1, t = c2[i] * x2 + c3[i] * x3, u = c4[i] * x4 + c5[i] * x5,
                v = c6[i] * x6 + c7[i] * x7;
    store4(y + 4 * i, load4(y + 4 * i) - ((s + t) + (u + v)));
  }
}

/// add_dots4 for eight columns: eight independent sums, v's row read once for eight.
[[gnu::always_inline]] inline void add_dots8(Lane4* r, int n, const double* c, std::size_t ld, const double* v) {
  const double *c0 = c, *c1 = c + ld, *c2 = c + 2 * ld, *c3 = c + 3 * ld, *c4 = c + 4 * ld, *c5 = c + 5 * ld,
               *c6 = c + 6 * ld, *c7 = c + 7 * ld;
  Lane4 s0 = {0.0, 0.0, 0.0, 0.0}, s1 = s0, s2 = s0, s3 = s0, s4 = s0, s5 = s0, s6 = s0, s7 = s0;
  for (int i = 0; i < n; ++i) {
    if ((i & 7) == 0) prefetch_columns8(c, ld, i);
    const Lane4 t = load4(v + 4 * i);
    s0 += c0[i] * t;
    s1 += c1[i] * t;
    s2 += c2[i] * t;
    s3 += c3[i] * t;
    s4 += c4[i] * t;
    s5 += c5[i] * t;
    s6 += c6[i] * t;
    s7 += c7[i] * t;
  }
  r[0] += s0;
  r[1] += s1;
  r[2] += s2;
  r[3] += s3;
  r[4] += s4;
  r[5] += s5;
  r[6] += s6;
  r[7] += s7;
}

/// y[i] -= sum over k < w of column k's entry i times x[k] (rows of four), w <= 8.
[[gnu::always_inline]] inline void subtract_block(double* y, int n, const double* c, std::size_t ld, const double* x,
                                                  int w) {
  if (w == 8) return subtract_columns8(y, n, c, ld, x);
  subtract_columns4(y, n, c, ld, x, w < 4 ? w : 4);
  if (w > 4) subtract_columns4(y, n, c + 4 * ld, ld, x + 16, w - 4);
}

/// r[k] += sum over i < n of column k's entry i times v[i] (rows of four), k < w <= 8.
[[gnu::always_inline]] inline void add_block_dots(Lane4* r, int n, const double* c, std::size_t ld, const double* v,
                                                  int w) {
  if (w == 8) return add_dots8(r, n, c, ld, v);
  add_dots4(r, n, c, ld, v, w < 4 ? w : 4);
  if (w > 4) add_dots4(r + 4, n, c + 4 * ld, ld, v, w - 4);
}

}  // namespace

PHEDRA_CPU_CLONES_V4 void supernodal_solve4(const SupernodalFactor& l, double* x, double* work) {
  // As supernodal_solve, a row being four values (one Lane4), and blocks of eight
  // columns: on the 10^4-panel array's factor the passes are bound by the loads
  // and stores a factor entry costs, not by memory (docs/performance.md).
  constexpr int block_width = 8;
  for (int s = 0; s < l.supernodes; ++s) {
    const auto [first, columns, below, ld, a, rows] = supernode(l, s);
    double* xs = x + 4 * static_cast<std::size_t>(first);
    for (int i = 0; i < 4 * below; ++i) work[i] = 0.0;
    for (int jb = 0; jb < columns; jb += block_width) {
      const int w = columns - jb < block_width ? columns - jb : block_width;
      const double* block = a + static_cast<std::size_t>(jb) * ld;
      for (int j = 0; j < w; ++j) {
        const double* column = block + static_cast<std::size_t>(j) * ld;
        const Lane4 xj = load4(xs + 4 * (jb + j)) / column[jb + j];
        store4(xs + 4 * (jb + j), xj);
        for (int i = j + 1; i < w; ++i) store4(xs + 4 * (jb + i), load4(xs + 4 * (jb + i)) - column[jb + i] * xj);
      }
      subtract_block(xs + 4 * (jb + w), columns - jb - w, block + jb + w, ld, xs + 4 * jb, w);
      subtract_block(work, below, block + columns, ld, xs + 4 * jb, w);
    }
    for (int i = 0; i < below; ++i) {
      double* target = x + 4 * static_cast<std::size_t>(rows[i]);
      store4(target, load4(target) + load4(work + 4 * i));  // work holds minus the products
    }
  }
  for (int s = l.supernodes - 1; s >= 0; --s) {
    const auto [first, columns, below, ld, a, rows] = supernode(l, s);
    double* xs = x + 4 * static_cast<std::size_t>(first);
    for (int i = 0; i < below; ++i) store4(work + 4 * i, load4(x + 4 * static_cast<std::size_t>(rows[i])));
    for (int jb = (columns - 1) / block_width * block_width; jb >= 0; jb -= block_width) {
      const int w = columns - jb < block_width ? columns - jb : block_width;
      const double* block = a + static_cast<std::size_t>(jb) * ld;
      Lane4 r[block_width] = {};
      add_block_dots(r, below, block + columns, ld, work, w);
      add_block_dots(r, columns - jb - w, block + jb + w, ld, xs + 4 * (jb + w), w);
      for (int j = w - 1; j >= 0; --j) {
        const double* column = block + static_cast<std::size_t>(j) * ld;
        Lane4 sum = r[j];
        for (int i = j + 1; i < w; ++i) sum += column[jb + i] * load4(xs + 4 * (jb + i));
        store4(xs + 4 * (jb + j), (load4(xs + 4 * (jb + j)) - sum) / column[jb + j]);
      }
    }
  }
}

}  // namespace phedra
