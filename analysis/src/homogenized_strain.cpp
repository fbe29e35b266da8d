#include "phedra/homogenized_strain.h"
#include "phedra/cpu_clones.h"

#include "phedra/errors.h"
#include "phedra/net_writer.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace phedra {
namespace {

/// The principal direction of the largest spread of `covariance` restricted to
/// the plane normal to `normal` (unit).
Vec3 widest_across(const Mat3& covariance, const Vec3& normal) {
  const Mat3 p = Mat3::Identity() - normal * normal.transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(p * covariance * p);  // ascending
  return solver.eigenvectors().col(2).normalized();
}

/// Largest component positive: the same design gives the same signs every time.
Vec3 signed_by_largest(Vec3 v) {
  Eigen::Index k;
  v.cwiseAbs().maxCoeff(&k);
  return v[k] < 0.0 ? Vec3(-v) : v;
}

}  // namespace

std::string to_string(MetricsAxes axes) { return axes == MetricsAxes::xyz ? "xyz" : "structural"; }

MetricsAxes parse_metrics_axes(const std::string& name) {
  if (name == "structural") return MetricsAxes::structural;
  if (name == "xyz") return MetricsAxes::xyz;
  throw InvalidInputError("--axes", "unknown axes \"" + name + "\" (use structural or xyz)");
}

HomogenizedStrain::HomogenizedStrain(const Assembly& assembly, MetricsAxes axes) : assembly_(assembly) {
  lo_ = assembly.flexion_interval().lower.t;
  hi_ = assembly.flexion_interval().upper.t;
  h_ = 1e-4 * (hi_ - lo_);
  assembly.evaluate(assembly.t_star(), configuration_);
  Vec3 mean = Vec3::Zero();
  std::size_t count = 0;
  for (const Points& m : configuration_.members) {
    for (const Vec3& p : m) mean += p;
    count += m.size();
  }
  mean /= static_cast<double>(count);
  anchor_ = mean;
  reference_.reserve(count);
  Mat3 covariance = Mat3::Zero();
  for (const Points& m : configuration_.members) {
    for (const Vec3& p : m) {
      reference_.push_back(p - mean);
      covariance += reference_.back() * reference_.back().transpose();
      reference_sum_ += reference_.back();
    }
  }
  canonical_anchor_ = assembly.base().frame().point_to_canonical(anchor_);
  // The pseudo-inverse: a design flat at t* has no spread across its plane.
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
  const double largest = solver.eigenvalues().maxCoeff();
  pseudo_inverse_ = Mat3::Zero();
  for (int k = 0; k < 3; ++k) {
    const double e = solver.eigenvalues()[k];
    if (e > 1e-12 * largest) pseudo_inverse_ += solver.eigenvectors().col(k) * solver.eigenvectors().col(k).transpose() / e;
  }

  if (axes == MetricsAxes::xyz) {
    axes_ = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  } else {
    // Along the trajectory: each member's chord from its first profile's centroid
    // to its last's, turned to agree with the first member's, summed.
    Vec3 chord = Vec3::Zero(), first = Vec3::Zero();
    for (std::size_t m = 0; m < assembly.member_count(); ++m) {
      const GridTopology& g = assembly.topology(m);
      const Points& x = configuration_.members[m];
      Vec3 a = Vec3::Zero(), b = Vec3::Zero();
      for (std::size_t c = 0; c < g.columns(); ++c) {
        a += x[g.index(0, c)];
        b += x[g.index(g.rows() - 1, c)];
      }
      Vec3 v = (b - a) / static_cast<double>(g.columns());
      if (m == 0) first = v;
      if (v.dot(first) < 0.0) v = -v;
      chord += v;
    }
    const double size = std::sqrt(covariance.trace() / static_cast<double>(count));
    Vec3 along;
    if (chord.norm() > 1e-9 * size) {
      along = chord.normalized();
    } else {  // a closed trajectory: its largest spread instead
      along = solver.eigenvectors().col(2).normalized();
    }
    const Vec3 across = signed_by_largest(widest_across(covariance, along));
    axes_ = {along, across, along.cross(across).normalized()};
  }
  const double trace = covariance.trace();
  for (int k = 0; k < 3; ++k) defined_[k] = axes_[k].dot(covariance * axes_[k]) > 1e-10 * trace;
}

void HomogenizedStrain::evaluate(double t) const { assembly_.evaluate(t, configuration_); }

PHEDRA_CPU_CLONES Mat3 HomogenizedStrain::moment(const std::vector<Points>& members) const {
  // sum (x - mean x)(X - mean X)^T = sum (x - a)(X - mean X)^T for any a (the X - mean X sum to
  // zero): one pass, a = the mean at t* keeping the numbers small.
  Mat3 out = Mat3::Zero();
  std::size_t k = 0;
  for (const Points& m : members) {
    for (const Vec3& p : m) out.noalias() += (p - anchor_) * reference_[k++].transpose();
  }
  return out;
}

Mat3 HomogenizedStrain::affine(double t) const {
  evaluate(t);
  return moment(configuration_.members) * pseudo_inverse_;
}

std::array<std::optional<double>, 3> HomogenizedStrain::stretch(double t) const {
  const Mat3 f = affine(t);
  std::array<std::optional<double>, 3> out;
  for (int k = 0; k < 3; ++k) {
    if (defined_[k]) out[k] = (f * axes_[k]).norm();
  }
  return out;
}

PHEDRA_CPU_CLONES Mat3 HomogenizedStrain::canonical_moment(const std::vector<NetState>& states, bool rates) const {
  // x = o + R p (p canonical; a rate: R p): sum (x - a) Y^T = R sum (p - c) Y^T + (o + R c - a) sum Y^T, c the
  // anchor in the canonical frame (o + R c = a but for rounding; a rate: c = 0 and o = 0), sum Y zero but for rounding.
  const Vec3 c = rates ? Vec3::Zero() : canonical_anchor_;
  Mat3 g = Mat3::Zero();
  const Vec3* y = reference_.data();  // in write_user's order: members, rows, columns
  for (std::size_t m = 0; m < states.size(); ++m) {
    const NetState& state = states[m];
    const std::size_t n = state.apexes.size() - 1, rows = assembly_.topology(m).rows();
    const bool closed = assembly_.closed(m);
    const double* s = state.apexes.data();
    for (std::size_t i = 0; i < rows; ++i) {
      const Vec3* axial = &state.axial[i * n];
      const Vec3* general = &state.general[i * n];
      if (!closed) g.noalias() += (NetWriter::canonical(false, n, 0, s, axial, general) - c) * (*y++).transpose();
      for (std::size_t j = 0; j < (closed ? n - 1 : n); ++j) g.noalias() += (general[j] - c) * (*y++).transpose();
      if (!closed) g.noalias() += (NetWriter::canonical(false, n, n + 1, s, axial, general) - c) * (*y++).transpose();
    }
  }
  const CanonicalFrame& frame = assembly_.base().frame();
  const Mat3 to_user = frame.rotation().transpose();
  const Vec3 shift = (rates ? Vec3::Zero() : Vec3(frame.origin() + to_user * c)) - anchor_;
  return to_user * g + shift * reference_sum_.transpose();
}

Points HomogenizedStrain::weights(const std::vector<std::uint32_t>& point_of, std::size_t points) const {
  if (point_of.size() != reference_.size()) {
    throw Error(ExitCode::internal, "strain weights: " + std::to_string(point_of.size()) + " vertices, expected " +
                                        std::to_string(reference_.size()));
  }
  Points out(points, Vec3::Zero());
  for (std::size_t k = 0; k < point_of.size(); ++k) out.at(point_of[k]) += reference_[k];
  return out;
}

HomogenizedStrain::State HomogenizedStrain::state_of(const Points& x, const Points* rates, const Points& weights) const {
  // (weighted_moment: strain_moment.cpp)
  return state_from(weighted_moment(x, weights) * pseudo_inverse_,
                    rates ? std::optional<Mat3>(weighted_moment(*rates, weights) * pseudo_inverse_) : std::nullopt);
}

void HomogenizedStrain::states_of_lanes(const double* x, const double* rates, const Points& weights, State* out) const {
  std::array<Mat3, lanes> moment, rate_moment;
  weighted_moments_lanes(x, weights, moment.data());
  if (rates) weighted_moments_lanes(rates, weights, rate_moment.data());
  for (std::size_t l = 0; l < lanes; ++l) {
    out[l] = state_from(moment[l] * pseudo_inverse_,
                        rates ? std::optional<Mat3>(rate_moment[l] * pseudo_inverse_) : std::nullopt);
  }
}

HomogenizedStrain::State HomogenizedStrain::state_from(const Mat3& f, const std::optional<Mat3>& df) const {
  State s;
  for (int k = 0; k < 3; ++k) {
    if (!defined_[k]) continue;
    const Vec3 fd = f * axes_[k];
    const double stretch = fd.norm();
    s.stretch[k] = stretch;
    if (df && stretch > 0.0) s.rate[k] = fd.dot(*df * axes_[k]) / (stretch * stretch);
  }
  return s;
}

HomogenizedStrain::State HomogenizedStrain::state_of(const AssemblyConfiguration& c, const std::vector<Points>* rates) const {
  // (the reference is centred: M is linear, so dF/dt = M(dx/dt) C^+)
  return state_from(moment(c.members) * pseudo_inverse_,
                    rates ? std::optional<Mat3>(moment(*rates) * pseudo_inverse_) : std::nullopt);
}

HomogenizedStrain::State HomogenizedStrain::state_of(const std::vector<NetState>& states,
                                                     const std::vector<NetState>* rates) const {
  return state_from(canonical_moment(states, false) * pseudo_inverse_,
                    rates ? std::optional<Mat3>(canonical_moment(*rates, true) * pseudo_inverse_) : std::nullopt);
}

HomogenizedStrain::State HomogenizedStrain::at(double t) const {
  // F's derivative: M is linear in the positions, so dF/dt = M(dx/dt) C^+ with
  // the exact dx/dt (Assembly::evaluate_rate). At a flexion limit, where it is
  // infinite, the fourth-order central difference next to it, its stencil inside
  // the interval (the rate the plots show at the ends).
  std::vector<Points> rates;
  if (assembly_.evaluate_rate(t, configuration_, rates)) return state_of(configuration_, &rates);
  State s;
  Mat3 df = Mat3::Zero();
  if (h_ > 0.0) {
    const double c = std::clamp(t, std::min(lo_ + 2.0 * h_, 0.5 * (lo_ + hi_)), std::max(hi_ - 2.0 * h_, 0.5 * (lo_ + hi_)));
    const std::array<std::pair<double, double>, 4> stencil{{{-2.0, 1.0}, {-1.0, -8.0}, {1.0, 8.0}, {2.0, -1.0}}};
    for (const auto& [offset, weight] : stencil) df += weight * affine(c + offset * h_);
    df /= 12.0 * h_;
  }
  const Mat3 f = affine(t);  // last: configuration() is the one at t
  for (int k = 0; k < 3; ++k) {
    if (!defined_[k]) continue;
    const Vec3 fd = f * axes_[k];
    const double stretch = fd.norm();
    s.stretch[k] = stretch;
    if (stretch > 0.0) s.rate[k] = fd.dot(df * axes_[k]) / (stretch * stretch);
  }
  return s;
}

}  // namespace phedra
