// Nesting pieces on pages by their shapes, not their boxes (issue 27: the
// grid-3x3 sheets left a third of every page empty). Each page's content area
// is a grid of 1 mm cells; a piece takes the cells near its panels, tabs and
// called-out labels (within half the gap between pieces, plus the reach of a
// cell), so two pieces whose cells do not meet are at least the gap apart,
// exactly; a zigzag strip then fits into the next one's notches.

#include "cut_sheet_parts.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace phedra::sheets {
namespace {

constexpr int word_bits = 64;

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double length2 = d.squaredNorm();
  const double u = length2 > 0.0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + u * d)).norm();
}

bool near_polygon(const Polygon2& polygon, const Vec2& p, double reach) {
  if (polygon.size() >= 3 && inside(polygon, p)) return true;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    if (distance_to_segment(p, polygon[k], polygon[(k + 1) % polygon.size()]) <= reach) return true;
  }
  return false;
}

}  // namespace

CellMask::CellMask(int width, int height) : width_(width), height_(height), words_((width + word_bits - 1) / word_bits + 1) {
  bits_.assign(static_cast<std::size_t>(height_) * static_cast<std::size_t>(words_), 0);
}

bool CellMask::get(int x, int y) const {
  return (row(y)[x / word_bits] >> (x % word_bits)) & 1U;
}

void CellMask::set(int x, int y) { row(y)[x / word_bits] |= std::uint64_t{1} << (x % word_bits); }

CellMask CellMask::of_shapes(const std::vector<Polygon2>& shapes, const Vec2& size, double cell, double reach, int pad) {
  const int width = static_cast<int>(std::ceil(size.x() / cell)) + 2 * pad;
  const int height = static_cast<int>(std::ceil(size.y() / cell)) + 2 * pad;
  CellMask mask(width, height);
  const double r = reach + 0.5 * std::sqrt(2.0) * cell;  // (a cell's centre stands for all of it)
  for (const Polygon2& shape : shapes) {
    Vec2 lo = shape.front(), hi = shape.front();
    for (const Vec2& p : shape) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const int x0 = std::max(0, static_cast<int>(std::floor((lo.x() - r) / cell)) + pad);
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil((hi.x() + r) / cell)) + pad);
    const int y0 = std::max(0, static_cast<int>(std::floor((lo.y() - r) / cell)) + pad);
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil((hi.y() + r) / cell)) + pad);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if (mask.get(x, y)) continue;
        const Vec2 centre((x - pad + 0.5) * cell, (y - pad + 0.5) * cell);
        if (near_polygon(shape, centre, r)) mask.set(x, y);
      }
    }
  }
  // The words to test, the fullest first: a conflict shows soonest there.
  for (int y = 0; y < height; ++y) {
    for (int k = 0; k + 1 < mask.words_; ++k) {
      if (const std::uint64_t bits = mask.row(y)[k]) mask.taken_.push_back({y, k, bits});
    }
  }
  std::stable_sort(mask.taken_.begin(), mask.taken_.end(),
                   [](const Word& a, const Word& b) { return std::popcount(a.bits) > std::popcount(b.bits); });
  return mask;
}

bool CellMask::meets(const CellMask& other, int dx, int dy) const {
  // other's cell (i, j) lies on this one's (dx + i, dy + j); dx, dy >= 0 and other within this.
  const int shift = dx % word_bits, first = dx / word_bits;
  for (const Word& w : other.taken_) {
    const std::uint64_t* mine = row(dy + w.row);
    std::uint64_t here = mine[first + w.index] >> shift;
    if (shift != 0) here |= mine[first + w.index + 1] << (word_bits - shift);
    if (here & w.bits) return true;
  }
  return false;
}

void CellMask::add(const CellMask& other, int dx, int dy) {
  for (int j = 0; j < other.height_; ++j) {
    for (int i = 0; i < other.width_; ++i) {
      if (other.get(i, j)) set(dx + i, dy + j);
    }
  }
}

std::optional<std::pair<int, int>> CellMask::highest_fit(const CellMask& piece, int max_x, int max_y) const {
  for (int y = max_y; y >= 0; --y) {
    for (int x = 0; x <= max_x; ++x) {
      if (!meets(piece, x, y)) return std::pair{x, y};
    }
  }
  return std::nullopt;
}

}  // namespace phedra::sheets
