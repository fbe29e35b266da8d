// Chains a page's cut segments into loops (cut_loops.h).

#include "phedra/cut_loops.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>

namespace phedra {

CutLoops cut_loops(const std::vector<SheetLine>& lines, double tolerance) {
  // Ends are matched on a grid of cells `tolerance` wide (and their neighbours):
  // the same corner drawn twice differs by rounding only.
  std::vector<std::pair<Vec2, Vec2>> segments;
  for (const SheetLine& l : lines) {
    if (l.style == LineStyle::cut && !l.key && (l.a - l.b).norm() > tolerance) segments.emplace_back(l.a, l.b);
  }
  using Cell = std::pair<std::int64_t, std::int64_t>;
  auto cell = [&](const Vec2& p) {
    return Cell{static_cast<std::int64_t>(std::floor(p.x() / tolerance)), static_cast<std::int64_t>(std::floor(p.y() / tolerance))};
  };
  std::multimap<Cell, std::size_t> ends;  // end 2 k (a) and 2 k + 1 (b) of segment k
  for (std::size_t k = 0; k < segments.size(); ++k) {
    ends.emplace(cell(segments[k].first), 2 * k);
    ends.emplace(cell(segments[k].second), 2 * k + 1);
  }
  std::vector<bool> used(segments.size(), false);
  auto end_point = [&](std::size_t e) { return e % 2 ? segments[e / 2].second : segments[e / 2].first; };
  // An unused segment with an end at p: that end.
  auto next_at = [&](const Vec2& p) -> std::optional<std::size_t> {
    const Cell c = cell(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto [lo, hi] = ends.equal_range(Cell{c.first + dx, c.second + dy});
        for (auto it = lo; it != hi; ++it) {
          if (!used[it->second / 2] && (end_point(it->second) - p).norm() <= tolerance) return it->second;
        }
      }
    }
    return std::nullopt;
  };
  CutLoops out;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    if (used[k]) continue;
    used[k] = true;
    std::vector<Vec2> chain{segments[k].first, segments[k].second};
    const Vec2 start = segments[k].first;
    bool closed = false;
    while (true) {
      if (chain.size() > 2 && (chain.back() - start).norm() <= tolerance) {
        chain.pop_back();
        closed = true;
        break;
      }
      const std::optional<std::size_t> e = next_at(chain.back());
      if (!e) break;
      used[*e / 2] = true;
      chain.push_back(end_point(*e ^ 1));  // the segment's other end
    }
    if (closed) {
      out.closed.push_back(std::move(chain));
    } else {
      out.open.push_back(std::move(chain));
    }
  }
  std::stable_sort(out.closed.begin(), out.closed.end(), [](const Polygon2& a, const Polygon2& b) {
    return std::abs(signed_area2(a)) < std::abs(signed_area2(b));
  });
  return out;
}

}  // namespace phedra
