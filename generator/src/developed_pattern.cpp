#include "phedra/developed_pattern.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>

namespace phedra {
namespace {

std::string at(const std::string& field, std::size_t i) { return field + "[" + std::to_string(i) + "]"; }

}  // namespace

DevelopedPattern::DevelopedPattern(DevelopedInput input) : input_(std::move(input)) {
  const auto& v = input_.trajectory;
  const auto& h = input_.apex_heights;
  if (v.size() < 2) throw InvalidInputError("developed.trajectory", "at least 2 points (one strip)");
  if (h.size() < 3) throw InvalidInputError("developed.apex_heights", "at least 3 heights (n >= 2)");
  if (input_.signs.size() != h.size() - 2) {
    throw InvalidInputError("developed.signs", "expected " + std::to_string(h.size() - 2) + " signs (one per inner apex), got " +
                                                   std::to_string(input_.signs.size()));
  }
  double extent = 0.0;
  for (const Vec2& p : v) extent = std::max({extent, std::abs(p.x()), std::abs(p.y())});
  for (double z : h) extent = std::max(extent, std::abs(z));
  const double tiny = 1e-12 * std::max(extent, 1e-300);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::abs(v[i].x()) <= tiny) {
      throw InvalidInputError(at("developed.trajectory", i), "lies on the axis (x = 0): its profile plane is undefined");
    }
    if (i > 0 && (v[i] - v[i - 1]).norm() <= tiny) {
      throw InvalidInputError(at("developed.trajectory", i), "coincides with the previous point");
    }
  }
  for (std::size_t j = 0; j + 1 < h.size(); ++j) {
    if (std::abs(h[j + 1] - h[j]) <= tiny) throw InvalidInputError(at("developed.apex_heights", j + 1), "equals the previous height");
    if (j + 2 < h.size() && std::abs(h[j + 2] - h[j]) <= tiny) {
      throw InvalidInputError(at("developed.apex_heights", j + 2), "equals apex height " + std::to_string(j) +
                                                                      ": the map about S_" + std::to_string(j + 1) +
                                                                      " degenerates");
    }
  }
  // Flat profiles: sigma+- about S_{j+1} in the plane (MATH.md section 2).
  const std::size_t n = h.size() - 1;
  flat_.assign(v.size(), std::vector<Vec2>(n));
  ratio_.assign(v.size(), std::vector<double>(n - 1));
  for (std::size_t i = 0; i < v.size(); ++i) {
    flat_[i][0] = v[i];
    for (std::size_t j = 0; j + 1 < n; ++j) {
      const double c = h[j + 1];
      const Vec2 centre(0.0, c);
      const Vec2& x = flat_[i][j];
      double rho = (h[j + 2] - c) / (h[j] - c);
      if (input_.signs[j] == Sign::minus) {
        const double denominator = 2.0 * (x.y() - c) - (h[j] - c);
        if (std::abs(denominator) <= 1e-9 * std::max(extent, 1e-300)) {
          throw InvalidInputError(at("developed.trajectory", i), "profile vertex " + std::to_string(j + 1) +
                                                                     " goes to infinity (on the vanishing line of the "
                                                                     "sign '-' at S_" + std::to_string(j + 1) + ")");
        }
        rho = (h[j + 2] - c) / denominator;
      }
      ratio_[i][j] = rho;
      flat_[i][j + 1] = centre + rho * (x - centre);
    }
  }
  for (const auto& row : flat_) {
    for (const Vec2& p : row) extent = std::max({extent, std::abs(p.x()), std::abs(p.y())});
  }
  size_ = 2.0 * std::sqrt(2.0) * extent;
  const Vec2 s0(0.0, h[0]), s1(0.0, h[1]);
  for (std::size_t i = 0; i < v.size(); ++i) {
    r0_.push_back((v[i] - s0).norm());
    r1_.push_back((v[i] - s1).norm());
    edge_.push_back(i ? (v[i] - v[i - 1]).norm() : 0.0);
  }
  if (std::abs(r0_[0] - r1_[0]) <= 1e-12 * size_) {
    throw InvalidInputError("developed.trajectory[0]", "is as far from S_0 as from S_1: the scissor case, whose motion "
                                                       "this construction does not cover");
  }
  case_ = r0_[0] < r1_[0] ? MotionCase::a : MotionCase::b;
  t_star_ = case_ == MotionCase::a ? h[0] : h[1];
  if (!in_plane(t_star_)) throw Error(ExitCode::internal, "the developed pattern is not real at t*");
}

std::optional<std::vector<double>> DevelopedPattern::apex_heights(double t) const {
  const auto p = in_plane(t);
  if (!p) return std::nullopt;
  // in_plane keeps the apexes as the last row.
  std::vector<double> out;
  for (const Vec2& s : p->back()) out.push_back(s.y());
  return out;
}

std::optional<std::vector<std::vector<Vec2>>> DevelopedPattern::in_plane(double t) const {
  const auto& h = input_.apex_heights;
  const std::size_t n = h.size() - 1, rows = flat_.size();
  const double z00 = flat_[0][0].y(), side0 = flat_[0][0].x() > 0 ? 1.0 : -1.0;
  // L_0: the moving apex at height t, V_00 keeps its height and its distances.
  std::vector<Vec2> s(n + 1);
  // Case (a) moves S_0 to height t, case (b) S_1; the other apex stays on the axis
  // where the first radii of both allow, on the side it starts on.
  const std::size_t moving = case_ == MotionCase::a ? 0 : 1, fixed = 1 - moving;
  const double r_moving = moving == 0 ? r0_[0] : r1_[0], r_fixed = moving == 0 ? r1_[0] : r0_[0];
  const double x2 = r_moving * r_moving - (t - z00) * (t - z00);
  if (x2 < 0.0) return std::nullopt;
  const double other = r_fixed * r_fixed - x2;
  if (other < 0.0) return std::nullopt;
  s[moving] = Vec2(0.0, t);
  s[fixed] = Vec2(0.0, z00 + (h[fixed] >= z00 ? 1.0 : -1.0) * std::sqrt(other));
  std::vector<std::vector<Vec2>> p(rows + 1, std::vector<Vec2>(n));
  p[0][0] = Vec2(side0 * std::sqrt(x2), z00);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double rho = ratio_[0][j];
    p[0][j + 1] = s[j + 1] + rho * (p[0][j] - s[j + 1]);
    Vec2 back = s[j] - p[0][j];
    if (input_.signs[j] == Sign::minus) back.y() = -back.y();
    s[j + 2] = p[0][j + 1] + rho * back;
    s[j + 2].x() = 0.0;
  }
  for (std::size_t i = 1; i < rows; ++i) {
    const double s0 = s[0].y(), s1 = s[1].y();
    const double z = 0.5 * (s0 + s1) + (r0_[i] * r0_[i] - r1_[i] * r1_[i]) / (2.0 * (s1 - s0));
    const double r2 = r0_[i] * r0_[i] - (z - s0) * (z - s0);
    if (r2 < 0.0) return std::nullopt;
    p[i][0] = Vec2((flat_[i][0].x() > 0 ? 1.0 : -1.0) * std::sqrt(r2), z);
    for (std::size_t j = 0; j + 1 < n; ++j) p[i][j + 1] = s[j + 1] + ratio_[i][j] * (p[i][j] - s[j + 1]);
  }
  // The apexes ride along as an extra row (n + 1 of them: the row gets resized).
  p[rows] = s;
  return p;
}

std::optional<double> DevelopedPattern::cos_turn(std::size_t i, const std::vector<std::vector<Vec2>>& p) const {
  const Vec2 a = p[i][0], b = p[i - 1][0];
  return (a.x() * a.x() + b.x() * b.x() + (a.y() - b.y()) * (a.y() - b.y()) - edge_[i] * edge_[i]) /
         (2.0 * a.x() * b.x());
}

std::optional<Points> DevelopedPattern::folded(double t, const std::vector<int>& fold) const {
  if (fold.size() != strips()) throw InvalidInputError("--fold", "expected " + std::to_string(strips()) + " fold choices");
  const auto p = in_plane(t);
  if (!p) return std::nullopt;
  const std::size_t rows = flat_.size(), n = columns();
  Points out;
  out.reserve(rows * n);
  double phi = 0.0;
  for (std::size_t i = 0; i < rows; ++i) {
    if (i > 0) {
      const double c = *cos_turn(i, *p);
      if (c > 1.0 + 1e-12 || c < -1.0 - 1e-12) return std::nullopt;
      phi += fold[i - 1] * std::acos(std::clamp(c, -1.0, 1.0));
    }
    for (std::size_t j = 0; j < n; ++j) {
      const Vec2& q = (*p)[i][j];
      out.emplace_back(q.x() * std::cos(phi), q.x() * std::sin(phi), q.y());
    }
  }
  return out;
}

std::vector<FlexDirection> DevelopedPattern::flex_directions() const {
  std::vector<FlexDirection> out;
  const std::size_t rows = flat_.size(), n = columns();
  const double hv = 1e-7 * size_;
  const auto before = in_plane(t_star_ - hv), after = in_plane(t_star_ + hv);
  for (int direction : {1, -1}) {
    FlexDirection f;
    f.direction = direction;
    const auto near = in_plane(t_star_ + direction * 1e-6 * size_);
    const auto further = in_plane(t_star_ + direction * 1e-4 * size_);
    if (!near || !further || !before || !after) {
      f.reason = "the linkage L_0 cannot move that way (V_00 would leave its plane)";
      f.expansion.assign(strips(), 0.0);
      f.strip_folds.assign(strips(), false);
      out.push_back(f);
      continue;
    }
    f.folds = true;
    for (std::size_t i = 1; i < rows; ++i) {
      // Paper's criterion: velocities of the planar linkage (central differences of the exact motion).
      double worst = -std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < n; ++j) {
        const Vec2 vp = ((*after)[i - 1][j] - (*before)[i - 1][j]) / (2.0 * hv);
        const Vec2 vq = ((*after)[i][j] - (*before)[i][j]) / (2.0 * hv);
        const Vec2 pq = flat_[i - 1][j] - flat_[i][j];
        const double across = flat_[i - 1][j].x() * flat_[i][j].x() > 0.0 ? 1.0 : -1.0;
        worst = std::max(worst, direction * across * (vp - vq).dot(pq));
      }
      f.expansion.push_back(worst);
      // Exact: the strip's planes can turn apart just beyond t*.
      const bool moves = *cos_turn(i, *near) <= 1.0 + 1e-12 && *cos_turn(i, *further) <= 1.0 + 1e-12;
      f.strip_folds.push_back(moves);
      if (!moves && f.folds) {
        f.folds = false;
        f.reason = "strip " + std::to_string(i) + " would have to stretch: its trajectory edge expands (" +
                   format_human(worst) + ")";
      }
    }
    if (f.folds) {
      // How far: grow the step while the motion stays real, then bisect.
      const std::vector<int> valley(strips(), 1);
      double good = t_star_, step = 1e-4 * size_;
      while (step < 1e3 * size_ && folded(good + direction * step, valley)) {
        good += direction * step;
        step *= 2.0;
      }
      double bad = good + direction * step;
      for (int k = 0; k < 200 && std::abs(bad - good) > 1e-14 * size_; ++k) {
        const double mid = 0.5 * (good + bad);
        (folded(mid, valley) ? good : bad) = mid;
      }
      f.reach = good;
      if (const auto p = in_plane(good)) {
        f.flat_at_reach = true;
        for (std::size_t i = 1; i < rows; ++i) {
          f.flat_at_reach = f.flat_at_reach && std::abs(std::abs(*cos_turn(i, *p)) - 1.0) < 1e-9;
        }
      }
    }
    out.push_back(f);
  }
  return out;
}

ControlPolylines DevelopedPattern::folded_preset(double t, const std::vector<int>& fold) const {
  const std::optional<Points> x = folded(t, fold);
  if (!x) throw InvalidInputError("--at", "the pattern cannot fold to t = " + format_human(t));
  const auto s = apex_heights(t);
  ControlPolylines c;
  c.name = input_.name + " (folded)";
  const std::size_t n = columns();
  for (std::size_t i = 0; i < flat_.size(); ++i) {
    const Vec3& p = (*x)[i * n];
    c.trajectory.push_back(p);
    c.directions.push_back(Vec3(p.x(), p.y(), 0.0).normalized());
  }
  c.apex_heights = *s;
  c.signs = input_.signs;
  return c;
}

}  // namespace phedra
