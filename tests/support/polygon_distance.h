#pragma once
// The distance between two polygons that do not overlap, for tests of nesting
// (cut sheets, print beds): from a corner of one to an edge of the other.

#include "phedra/sheet_geometry.h"

#include <algorithm>
#include <limits>

namespace phedra::test {

inline double polygon_distance(const Polygon2& a, const Polygon2& b) {
  double d = std::numeric_limits<double>::infinity();
  for (int side = 0; side < 2; ++side) {
    const Polygon2& p = side ? b : a;
    const Polygon2& q = side ? a : b;
    for (const Vec2& c : p) {
      for (std::size_t k = 0; k < q.size(); ++k) {
        const Vec2 e0 = q[k], e1 = q[(k + 1) % q.size()];
        const double l2 = (e1 - e0).squaredNorm();
        const double u = l2 > 0.0 ? std::clamp((c - e0).dot(e1 - e0) / l2, 0.0, 1.0) : 0.0;
        d = std::min(d, (c - (e0 + u * (e1 - e0))).norm());
      }
    }
  }
  return d;
}

}  // namespace phedra::test
