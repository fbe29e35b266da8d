#include "phedra/phedron.h"

#include "phedra/axial_net.h"
#include "phedra/errors.h"
#include "phedra/geometry_checks.h"
#include "phedra/number_format.h"
#include "phedra/parallel_net.h"
#include "phedra/tolerances.h"
#include "phedra/validation.h"

#include <cmath>
#include <string>

namespace phedra {
namespace {

CanonicalInput to_canonical(const ControlPolylines& in, const CanonicalFrame& frame) {
  CanonicalInput c;
  c.trajectory.reserve(in.trajectory.size());
  for (const Vec3& p : in.trajectory) c.trajectory.push_back(frame.point_to_canonical(p));
  for (const Vec3& d : in.directions) {
    Vec3 v = frame.vector_to_canonical(d);
    v.z() = 0.0;  // orthogonal to the axis up to the validated tolerance
    c.directions.push_back(v);
  }
  for (double h : in.apex_heights) c.heights.push_back(frame.height_to_canonical(h));
  c.signs = in.signs;
  c.scale = input_scale(in);
  return c;
}

/// The constructed general net at t* with its boundary columns, user frame.
Points reference_net(const AxialNet& axial, const ParallelNet& parallel, const CanonicalInput& in,
                     const CanonicalFrame& frame) {
  const std::size_t n = axial.columns;
  const Vec3 first(0, 0, in.heights.front()), last(0, 0, in.heights.back());
  Points out;
  out.reserve(axial.rows * (n + 2));
  for (std::size_t i = 0; i < axial.rows; ++i) {
    const Vec3* g = &parallel.vertices[i * n];
    out.push_back(frame.point_to_user(g[0] + (first - axial.vertex(i, 0))));
    for (std::size_t j = 0; j < n; ++j) out.push_back(frame.point_to_user(g[j]));
    out.push_back(frame.point_to_user(g[n - 1] + (last - axial.vertex(i, n - 1))));
  }
  return out;
}

}  // namespace

PHedron::PHedron(ControlPolylines input) : input_(std::move(input)) {
  validate(input_);
  frame_ = CanonicalFrame(input_);
  const CanonicalInput canonical = to_canonical(input_, frame_);
  const AxialNet axial = build_axial_net(canonical);
  const ParallelNet parallel = build_parallel_net(axial, canonical.trajectory);
  n_ = axial.columns;
  topology_ = GridTopology(axial.rows, n_ + 2, false);
  linkage_ = Linkage(axial, canonical);
  chain_ = StripChain(axial, canonical.heights[0], canonical.heights[1]);
  ratios_ = axial.ratios;
  transversal_scales_ = parallel.transversal_scales;
  reference_ = reference_net(axial, parallel, canonical, frame_);
  for (const Vec3& p : reference_) {
    if (!p.allFinite()) {
      throw InvalidInputError("", "the construction overflows (a vertex is not finite): the input is too "
                                  "close to a degenerate configuration or its numbers are too large");
    }
  }
  model_size_ = bounding_box_diagonal(reference_);

  // t is the user's height of the moving apex: t* is that input height exactly, and
  // every t (search, checks, evaluate) goes through the same conversion.
  t_star_ = input_.apex_heights[motion_case() == MotionCase::a ? 0 : 1];
  const StripMargin at_star = margin(t_star_);
  auto bifurcation = [&](const StripMargin& m, const std::string& detail) {
    return InvalidInputError(m.strip == 0 ? std::string("trajectory[0]") : "directions[" + std::to_string(m.strip) + "]",
                             "the input is (numerically) in a bifurcation configuration: " + detail +
                                 " (paper, Remark 3); move it away from the flexion limit");
  };
  if (!(at_star.value > tolerance::bifurcation_margin)) {
    throw bifurcation(at_star, "strip " + std::to_string(at_star.strip) + " is at its flexion limit (margin " +
                                   format_number(at_star.value) + ")");
  }
  const double bound = linkage_.bound();
  interval_ = find_flexion_interval(t_star_, frame_.height_to_user(-bound), frame_.height_to_user(bound),
                                    [this](double t) { return margin(t); });
  if (!(interval_.lower.t < t_star_)) throw bifurcation({0, interval_.lower.strip}, "t* is the lower flexion limit");
  if (!(interval_.upper.t > t_star_)) throw bifurcation({0, interval_.upper.strip}, "t* is the upper flexion limit");
}

double PHedron::t_at_fraction(double fraction) const {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw InvalidInputError("fraction", "must be in [0, 1] (0: t_lambda, 1: t_mu), got " + format_number(fraction));
  }
  if (fraction == 1.0) return interval_.upper.t;
  return interval_.lower.t + fraction * interval_.width();
}

StripMargin PHedron::canonical_margin(double tc) const {
  LinkageStart start;
  double margin;
  if (!linkage_.start(tc, start, margin)) return {-1.0, 0};
  StripMargin worst = chain_.trace(start.s0, start.s1, Vec3(start.x, 0, 0), nullptr, 0);
  if (worst.value >= 0.0 && margin < worst.value) worst = {margin, 0};
  return worst;
}

StripMargin PHedron::margin(double t) const { return canonical_margin(canonical_t(t)); }

std::vector<double> PHedron::apex_heights(double t) const {
  if (!interval_.contains(t)) throw OutOfIntervalError(t, interval_.lower.t, interval_.upper.t);
  LinkageStart start;
  double margin;
  linkage_.start(canonical_t(t), start, margin);
  std::vector<double> s(n_ + 1);
  Points row(n_);
  linkage_.complete(start, s.data(), row.data());
  for (double& h : s) h = frame_.height_to_user(h);
  return s;
}

Points PHedron::evaluate(double t) const {
  Points out(vertex_count());
  evaluate(t, out);
  return out;
}

void PHedron::evaluate(double t, std::span<Vec3> out) const {
  if (!interval_.contains(t)) throw OutOfIntervalError(t, interval_.lower.t, interval_.upper.t);
  if (out.size() != vertex_count()) {
    throw Error(ExitCode::internal, "evaluate: output has " + std::to_string(out.size()) + " entries, expected " +
                                        std::to_string(vertex_count()));
  }
  const std::size_t n = n_;
  const std::size_t columns = n + 2;
  LinkageStart start;
  double margin;
  if (!linkage_.start(canonical_t(t), start, margin)) start.x = 0.0;  // only at the bound, by rounding
  std::vector<double> s(n + 1);
  Points previous_a(n), current_a(n), previous_g(n), current_g(n);
  linkage_.complete(start, s.data(), current_a.data());
  current_g = current_a;

  const Mat3 to_user = frame_.rotation().transpose();
  const Vec3 origin = frame_.origin();
  const Vec3 first_apex(0, 0, s.front());
  const Vec3 last_apex(0, 0, s.back());
  auto write_row = [&](std::size_t i) {
    Vec3* row = out.data() + i * columns;
    row[0] = origin + to_user * (current_g[0] + (first_apex - current_a[0]));
    for (std::size_t j = 0; j < n; ++j) row[j + 1] = origin + to_user * current_g[j];
    row[n + 1] = origin + to_user * (current_g[n - 1] + (last_apex - current_a[n - 1]));
  };
  write_row(0);
  const std::size_t rows = topology_.rows();
  for (std::size_t i = 1; i < rows; ++i) {
    std::swap(previous_a, current_a);
    std::swap(previous_g, current_g);
    if (!chain_.advance(i, s[0], s[1], previous_a[0], current_a[0], margin, true)) {
      throw Error(ExitCode::internal, "evaluate: strip " + std::to_string(i) + " has no real position at t = " +
                                          format_number(t) + " inside the flexion interval");
    }
    const double* rho = &ratios_[i * (n - 1)];
    for (std::size_t j = 0; j + 1 < n; ++j) {
      const double c = s[j + 1];
      const Vec3& a = current_a[j];
      current_a[j + 1] = Vec3(rho[j] * a.x(), rho[j] * a.y(), c + rho[j] * (a.z() - c));
    }
    const double* q = &transversal_scales_[i * n];
    for (std::size_t j = 0; j < n; ++j) current_g[j] = previous_g[j] + q[j] * (current_a[j] - previous_a[j]);
    write_row(i);
  }
}

}  // namespace phedra
