#include "phedra/phedron.h"

#include "row_kernel.h"

#include "phedra/closed_profile.h"
#include "phedra/errors.h"
#include "phedra/geometry_checks.h"
#include "phedra/net_writer.h"
#include "phedra/number_format.h"
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

}  // namespace

PHedron::PHedron(ControlPolylines input) : input_(std::move(input)) {
  validate(input_);
  frame_ = CanonicalFrame(input_);
  canonical_ = to_canonical(input_, frame_);
  // The nets are built row by row straight into reference(): besides it, only
  // the constants of the motion are stored (memory: 40 bytes a vertex, 48 when
  // every sign is '+': the row coefficients of evaluate).
  const AxialColumn column = build_axial_column(canonical_);
  closed_ = has_closed_profile(input_);
  const std::size_t n = canonical_.heights.size() - 1;
  topology_ = GridTopology(column.vertices.size(), NetWriter::columns(closed_, n), closed_);
  reference_.assign(vertex_count(), Vec3::Zero());
  const NetWriter writer(frame_, closed_, n, reference_);
  ClosureGap gap;
  motion_ = NetMotion(canonical_, column, canonical_.trajectory, [&](std::size_t i, const Vec3* axial, const Vec3* general) {
    writer.write(i, canonical_.heights.data(), axial, general);
    const double d = (general[n - 1] - general[0]).norm();
    if (!(d <= gap.value)) gap = {d, i};
  });
  linkage_ = Linkage(column.vertices, canonical_);
  compute_row_coefficients();
  chain_ = StripChain(column.vertices, canonical_.heights[0], canonical_.heights[1]);
  for (const Vec3& p : reference_) {
    if (!p.allFinite()) {
      throw InvalidInputError("", "the construction overflows (a vertex is not finite): the input is too "
                                  "close to a degenerate configuration or its numbers are too large");
    }
  }
  model_size_ = bounding_box_diagonal(reference_);
  if (closed_) {
    if (!(gap.value <= tolerance::check_relative * model_size_)) {
      throw InvalidInputError("apex_heights", "the profile [" + std::to_string(n - 1) +
                                                  " sides, heights repeating their first two] does not close at t*: "
                                                  "gap " + format_number(gap.value) + " at row " +
                                                  std::to_string(gap.row) + " (MATH.md section 5)");
    }
  }

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
  interval_ = search_flexion_interval();
  if (!(interval_.lower.t < t_star_)) throw bifurcation({0, interval_.lower.strip}, "t* is the lower flexion limit");
  if (!(interval_.upper.t > t_star_)) throw bifurcation({0, interval_.upper.strip}, "t* is the upper flexion limit");
}

FlexionInterval PHedron::search_flexion_interval() const {
  const double bound = linkage_.bound();
  return find_flexion_interval(t_star_, frame_.height_to_user(-bound), frame_.height_to_user(bound),
                               [this](double t) { return margin(t); },
                               [this](double t, std::size_t strip) { return strip_margin(t, strip); });
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
  if (!linkage_.start(tc, start, margin)) return {margin, 0};
  StripMargin worst = chain_.margin(start.s0, start.s1, start.x);
  if (margin < worst.value) worst = {margin, 0};
  return worst;
}

StripMargin PHedron::margin(double t) const { return canonical_margin(canonical_t(t)); }

double PHedron::strip_margin(double t, std::size_t strip) const {
  LinkageStart start;
  double margin;
  if (!linkage_.start(canonical_t(t), start, margin) || strip == 0) return margin;
  return chain_.strip_margin(strip, start.s0, start.s1, start.x);
}

LinkageStart PHedron::start_at(double t) const {
  if (!interval_.contains(t)) throw OutOfIntervalError(t, interval_.lower.t, interval_.upper.t);
  LinkageStart start;
  double margin;
  if (!linkage_.start(canonical_t(t), start, margin)) start.x = 0.0;  // only at the bound, by rounding
  return start;
}

void PHedron::advance_column(std::size_t i, double t, const double* s, const Vec3& previous, Vec3& out,
                             const std::vector<bool>* flipped) const {
  double margin;
  if (!chain_.advance(i, s[0], s[1], previous, out, margin, true, flipped && (*flipped)[i])) {
    throw Error(ExitCode::internal, "evaluate: strip " + std::to_string(i) + " has no real position at t = " +
                                        format_number(t) + " inside the flexion interval");
  }
}

template <class RowSink>
void PHedron::run_rows(double t, const std::vector<bool>* flipped, RowSink&& sink) const {
  const LinkageStart start = start_at(t);
  const std::size_t n = motion_.columns();
  std::vector<double> s(n + 1);
  Points previous_a(n), current_a(n), previous_g(n), current_g(n);
  motion_.complete_first_row(start.s0, start.s1, Vec3(start.x, 0, 0), s.data(), current_a.data());
  current_g = current_a;
  sink(std::size_t{0}, s.data(), current_a.data(), current_g.data());
  for (std::size_t i = 1; i < motion_.rows(); ++i) {
    std::swap(previous_a, current_a);
    std::swap(previous_g, current_g);
    advance_column(i, t, s.data(), previous_a[0], current_a[0], flipped);
    motion_.fill_row(i, s.data(), current_a.data());
    motion_.advance_general_row(i, previous_a.data(), current_a.data(), previous_g.data(), current_g.data());
    sink(i, s.data(), current_a.data(), current_g.data());
  }
}

void PHedron::evaluate(double t, std::span<Vec3> out, ClosureGap* gap) const {
  evaluate_on(t, nullptr, out, gap);
}

void PHedron::evaluate(double t, const std::vector<bool>& flipped, std::span<Vec3> out, ClosureGap* gap) const {
  if (flipped.size() != motion_.rows()) {
    throw Error(ExitCode::internal, "evaluate: branch of " + std::to_string(flipped.size()) + " strips, expected " +
                                        std::to_string(motion_.rows()));
  }
  evaluate_on(t, &flipped, out, gap);
}

PHedron::ConfigurationCycle PHedron::configuration_cycle() const {
  ConfigurationCycle cycle;
  const std::vector<bool> input(motion_.rows(), false);
  std::vector<bool> branch = input;
  double t = t_star_;
  bool upward = true;
  std::size_t switched = 0;
  // At most: both ends switch two strips each before the input branch returns.
  for (int pass = 0; pass < 8; ++pass) {
    const FlexionLimit& end = upward ? interval_.upper : interval_.lower;
    const bool back_home = branch == input && pass > 0;
    const double to = back_home && (upward ? t_star_ >= t : t_star_ <= t) ? t_star_ : end.t;
    cycle.passes.push_back({t, to, branch, switched});
    if (to == t_star_ && back_home) {
      cycle.closed = true;
      return cycle;
    }
    if (end.strip == 0) {
      cycle.stop = std::string("t = ") + format_number(end.t) + ": the linkage L_0 reaches its limit (V_{0,0} on the "
                   "axis), which the motion cannot pass";
      return cycle;
    }
    branch[end.strip] = !branch[end.strip];
    switched = end.strip;
    t = end.t;
    upward = !upward;
  }
  cycle.stop = "the branches do not return to the input branch within 8 passes";
  return cycle;
}

void PHedron::compute_row_coefficients() {
  if (!motion_.uniform()) return;
  const std::size_t n = motion_.columns(), width = topology_.columns();
  const std::size_t shift = closed_ ? 0 : 1;
  const double* alpha = motion_.row_alphas(0);
  row_coefficients_.resize(motion_.rows() * width);
  for (std::size_t i = 0; i < motion_.rows(); ++i) {
    const double* q = motion_.row_scales(i);
    double* c = &row_coefficients_[i * width];
    for (std::size_t j = 0; j + shift < width && j < n; ++j) c[shift + j] = q[j] * alpha[j];
    if (closed_) continue;
    c[0] = q[0] - 1.0;                          // G_{-1} = G_0 + (S_0 - A_0)
    c[n + 1] = (q[n - 1] - 1.0) * alpha[n - 1];  // G_n = G_{n-1} + (S_n - A_{n-1})
  }
}

void PHedron::evaluate_on(double t, const std::vector<bool>* flipped, std::span<Vec3> out, ClosureGap* gap) const {
  if (out.size() != vertex_count()) {
    throw Error(ExitCode::internal, "evaluate: output has " + std::to_string(out.size()) + " entries, expected " +
                                        std::to_string(vertex_count()));
  }
  // The recursions of the motion are affine, so after column 0 (the strip chain,
  // canonical frame) every row runs in the user's frame and goes straight to `out`:
  // the rho recursion in closed form (NetMotion::row_alphas, row_offsets: no
  // vertex waits on the previous one) and one multiply-add of the general net.
  const LinkageStart start = start_at(t);
  const std::size_t n = motion_.columns();
  std::vector<double> s(n + 1);
  Points scratch(3 * n + 5);
  Vec3* const apex = scratch.data();    // S_0..S_n, user frame
  // The axial row (user frame) lies as the output's columns do modulo 32 bytes
  // (no vector store of the row loop straddles two cache lines more than the output's).
  Vec3* const axial = place_like(apex + n + 1, out.data() + (has_closed_profile(input_) ? 0 : 1));
  Vec3* const first_row = axial + n;    // row 0, canonical frame
  Vec3 column0(start.x, 0, 0);
  motion_.complete_first_row(start.s0, start.s1, column0, s.data(), first_row);
  const Vec3 axis = frame_.rotation().row(2).transpose();
  for (std::size_t j = 0; j <= n; ++j) apex[j] = frame_.origin() + s[j] * axis;
  for (std::size_t j = 0; j < n; ++j) axial[j] = frame_.point_to_user(first_row[j]);

  // The general net is written in place: row i of `out` from row i - 1. A closed
  // profile stores columns 0..n-2; its last column (= column 0 up to the closure
  // gap) is carried in `last`.
  const std::size_t width = topology_.columns();
  const std::size_t shift = closed_ ? 0 : 1;
  const std::size_t stored = closed_ ? n - 1 : n;
  Vec3 last = axial[n - 1];
  auto closure_gap = [&](std::size_t i, const Vec3* row) {
    const double d = (last - row[0]).norm();
    if (!(d <= gap->value)) *gap = {d, i};
  };
  auto finish_row = [&](std::size_t i, Vec3* general) {
    if (closed_) {
      if (gap) closure_gap(i, general);
      return;
    }
    general[-1] = general[0] + (apex[0] - axial[0]);
    general[n] = general[n - 1] + (apex[n] - axial[n - 1]);
  };
  if (gap) *gap = {};
  Vec3* general = out.data() + shift;
  std::copy(axial, axial + stored, general);
  finish_row(0, general);
  const bool uniform = motion_.uniform();
  // An output beyond the caches is streamed to memory (row_kernel.h): the rows
  // are advanced in a copy that stays in the cache (all signs '+': StreamCopy,
  // written out as it is computed; else `in_cache`, then copied out).
  const bool stream = stream_output(out.size() * sizeof(Vec3));
  StreamCopy copy(stream && uniform ? width : 0);
  Points in_cache_room(stream && !uniform ? width + 4 : 0);
  Vec3* const in_cache = stream && !uniform ? place_like(in_cache_room.data(), out.data()) : nullptr;
  StreamCarry carry;
  if (stream && uniform) copy.start(out.data());
  if (stream && !uniform) std::copy(out.data(), out.data() + width, in_cache);
  RowArguments row{nullptr, s.data(), nullptr, stored, Vec3::Zero(), frame_.origin(), axis, nullptr, nullptr, axial};
  Vec3 first = axial[0];  // A_{i,0}, user frame
  std::pair<std::size_t, std::size_t> streamed;  // columns of a row that advance_row streamed
  // The strip chain is serial (row i's trajectory vertex from row i - 1's, a few
  // square roots a row): the next row's is issued before this row's vertices, so
  // that the processor overlaps its latency with them.
  Vec3 next;
  if (motion_.rows() > 1) advance_column(1, t, s.data(), column0, next, flipped);
  for (std::size_t i = 1; i < motion_.rows(); ++i) {
    column0 = next;
    if (i + 1 < motion_.rows()) advance_column(i + 1, t, s.data(), column0, next, flipped);
    const double* rho = motion_.row_ratios(i);
    const double* q = motion_.row_scales(i);
    const Vec3* previous = general;
    general += width;
    const Vec3 a0 = frame_.point_to_user(column0);
    if (uniform) {
      // Every row shares alpha and b: the rows differ by alpha_j (a0 - previous a0),
      // the boundary columns included (row_coefficients_).
      const double* alpha = motion_.row_alphas(0);
      const Vec3 delta = a0 - first;
      Vec3* const row_start = general - shift;
      const UniformRowArguments arguments{&row_coefficients_[i * width], width, delta, row_start - width, row_start};
      if (stream) {
        const StreamCopy::Place place = copy.next(row_start);
        advance_uniform_row_streaming({arguments.c, width, delta, place.previous, row_start}, place.copy, carry);
      } else {
        advance_uniform_row(arguments);
      }
      if (closed_) last += (q[n - 1] * alpha[n - 1]) * delta;
    } else {
      row.rho = rho;
      row.q = q;
      row.first = a0;
      row.previous = stream ? in_cache + shift : previous;
      row.general = stream ? in_cache + shift : general;
      row.stream_to = stream ? general : nullptr;
      const RowResult result = advance_row(row);
      streamed = {result.streamed_begin + shift, result.streamed_end + shift};
      const Vec3& a = result.last_axial;
      if (closed_) {
        const Vec3& c = apex[n - 1];
        const Vec3 end = c + rho[n - 2] * (a - c);
        last += q[n - 1] * (end - axial[n - 1]);
        axial[n - 1] = end;
      }
    }
    first = a0;
    if (!uniform) {
      finish_row(i, stream ? in_cache + shift : general);
      if (stream) {  // the columns the row loop did not stream, in order
        stream_row(in_cache, general - shift, streamed.first, carry);
        stream_row(in_cache + streamed.second, general - shift + streamed.second, width - streamed.second, carry);
      }
    } else if (closed_ && gap) {
      closure_gap(i, stream ? copy.last() : general);  // (an open row's boundary columns are in the row)
    }
  }
  if (stream) streaming_done(carry);
}

Points PHedron::evaluate(double t) const {
  Points out(vertex_count());
  evaluate(t, out);
  return out;
}

void PHedron::evaluate_canonical(double t, Points& axial, Points& general, std::vector<double>& apexes,
                                 const std::vector<bool>* flipped) const {
  const std::size_t n = motion_.columns();
  axial.resize(motion_.rows() * n);
  general.resize(motion_.rows() * n);
  apexes.resize(n + 1);
  run_rows(t, flipped, [&](std::size_t i, const double* s, const Vec3* a, const Vec3* g) {
    std::copy(a, a + n, axial.begin() + i * n);
    std::copy(g, g + n, general.begin() + i * n);
    if (i == 0) std::copy(s, s + n + 1, apexes.begin());
  });
}

bool PHedron::evaluate_canonical_rate(double t, NetState& state, NetState& rate,
                                      const std::vector<bool>* flipped) const {
  const LinkageStart start = start_at(t);
  LinkageStart d;
  // At the flexion limits the rate is infinite (a square root's at zero): the
  // limits are known to about 1e-12, where the computed rate is merely large.
  bool finite = t != interval_.lower.t && t != interval_.upper.t && linkage_.rate(canonical_t(t), start, d);
  const std::size_t n = motion_.columns(), rows = motion_.rows();
  for (NetState* x : {&state, &rate}) {
    x->axial.resize(rows * n);
    x->general.resize(rows * n);
    x->apexes.resize(n + 1);
  }
  motion_.complete_first_row(start.s0, start.s1, Vec3(start.x, 0, 0), state.apexes.data(), state.axial.data());
  motion_.complete_first_row(d.s0, d.s1, Vec3(d.x, 0, 0), rate.apexes.data(), rate.axial.data());
  std::copy(state.axial.begin(), state.axial.begin() + n, state.general.begin());
  std::copy(rate.axial.begin(), rate.axial.begin() + n, rate.general.begin());
  const double* s = state.apexes.data();
  const double* ds = rate.apexes.data();
  for (std::size_t i = 1; i < rows; ++i) {
    const Vec3& previous = state.axial[(i - 1) * n];
    Vec3& a0 = state.axial[i * n];
    advance_column(i, t, s, previous, a0, flipped);
    finite = finite && chain_.rate(s[0], s[1], previous, a0, ds[0], ds[1], rate.axial[(i - 1) * n], rate.axial[i * n]);
    for (NetState* x : {&state, &rate}) {
      Vec3* row = &x->axial[i * n];
      motion_.fill_row(i, x->apexes.data(), row);
      motion_.advance_general_row(i, row - n, row, &x->general[(i - 1) * n], &x->general[i * n]);
    }
  }
  return finite;
}

std::vector<double> PHedron::apex_heights(double t) const {
  const LinkageStart start = start_at(t);
  std::vector<double> heights(motion_.columns() + 1);
  Points row(motion_.columns());
  motion_.complete_first_row(start.s0, start.s1, Vec3(start.x, 0, 0), heights.data(), row.data());
  for (double& h : heights) h = frame_.height_to_user(h);
  return heights;
}

}  // namespace phedra
