#include "phedra/metamaterial_metrics.h"
#include "phedra/report_values.h"
#include "phedra/plot_axes.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <cmath>
#include <ostream>
#include <sstream>

namespace phedra {

std::array<double, 3> axis_extents(const std::vector<Points>& members, const std::array<Vec3, 3>& d) {
  std::array<double, 3> out{};
  for (int k = 0; k < 3; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Points& m : members) {
      for (const Vec3& p : m) {
        const double s = d[k].dot(p);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
    }
    out[k] = hi - lo;
  }
  return out;
}

namespace {

/// The figures at t; `reference` holds the lengths at t* (the bounding extents then), none for t* itself.
MetricsSample sample_at(const HomogenizedStrain& strain, const Assembly& a, double t,
                        const std::array<std::optional<double>, 3>* reference) {
  MetricsSample s;
  s.t = t;
  const HomogenizedStrain::State state = strain.at(t);
  const std::vector<Points>& members = strain.configuration().members;
  s.bounding_extent = axis_extents(members, strain.axes());
  s.strain_rate = state.rate;
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> at_star = reference ? (*reference)[k] : std::optional<double>(s.bounding_extent[k]);
    if (state.stretch[k] && at_star) s.length[k] = *at_star * *state.stretch[k];
  }
  double total = 0.0;
  bool any = false;
  for (std::size_t m = 0; m < a.member_count(); ++m) {
    if (a.closed(m)) {
      const double v = enclosed_volume(a.topology(m), members[m]);
      s.member_volume.push_back(v);
      total += v;
      any = true;
    } else {
      s.member_volume.push_back(std::nullopt);
    }
  }
  if (any) s.volume = total;
  // Poisson's ratios from the strain rates d ln(L)/dt (homogenized_strain.h).
  const double width = a.flexion_interval().upper.t - a.flexion_interval().lower.t;
  const std::array<std::pair<int, int>, 3> pairs{{{0, 1}, {0, 2}, {1, 2}}};
  for (int p = 0; p < 3; ++p) {
    const auto [j, k] = pairs[p];
    if (!state.rate[j] || !state.rate[k]) continue;
    const double rj = *state.rate[j], rk = *state.rate[k];
    if (std::abs(rj) * width > 1e-7 && std::isfinite(rk / rj)) s.poisson[p] = -rk / rj;
  }
  return s;
}


nlohmann::json sample_json(const MetricsSample& s) {
  nlohmann::json members = nlohmann::json::array();
  for (const auto& v : s.member_volume) members.push_back(optional_json(v));
  return {{"t", s.t},
          {"length", {optional_json(s.length[0]), optional_json(s.length[1]), optional_json(s.length[2])}},
          {"bounding_extent", s.bounding_extent},
          {"strain_rate", {optional_json(s.strain_rate[0]), optional_json(s.strain_rate[1]), optional_json(s.strain_rate[2])}},
          {"volume", optional_json(s.volume)},
          {"member_volume", members},
          {"poisson", {{"nu_12", optional_json(s.poisson[0])},
                       {"nu_13", optional_json(s.poisson[1])},
                       {"nu_23", optional_json(s.poisson[2])}}}};
}


}  // namespace

double enclosed_volume(const GridTopology& g, const Points& x) {
  if (!g.cyclic()) return 0.0;
  // Divergence theorem over the side panels and the two end profiles, oriented
  // consistently: each triangle (a, b, c) adds a . (b x c) / 6.
  double six = 0.0;
  auto triangle = [&](const Vec3& a, const Vec3& b, const Vec3& c) { six += a.dot(b.cross(c)); };
  const Vec3 o = x[0];  // relative to a vertex of the tube: better conditioned
  for (std::size_t k = 0; k < g.face_count(); ++k) {
    const Quad q = g.face(k);
    triangle(x[q[0]] - o, x[q[1]] - o, x[q[2]] - o);
    triangle(x[q[0]] - o, x[q[2]] - o, x[q[3]] - o);
  }
  const std::size_t last = g.rows() - 1;
  for (std::size_t c = 1; c + 1 < g.columns(); ++c) {
    triangle(x[g.index(0, 0)] - o, x[g.index(0, c + 1)] - o, x[g.index(0, c)] - o);  // reversed: first profile
    triangle(x[g.index(last, 0)] - o, x[g.index(last, c)] - o, x[g.index(last, c + 1)] - o);
  }
  return std::abs(six) / 6.0;
}

namespace {

/// Largest over smallest of a positive series (none when a value is missing or 0).
std::optional<double> deployment(const std::vector<MetricsSample>& samples,
                                 const std::function<std::optional<double>(const MetricsSample&)>& value) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const MetricsSample& s : samples) {
    const std::optional<double> v = value(s);
    if (!v || !std::isfinite(*v)) return std::nullopt;
    lo = std::min(lo, *v);
    hi = std::max(hi, *v);
  }
  return lo > 0.0 ? std::optional<double>(hi / lo) : std::nullopt;
}

const char* const axis_meaning[2][3] = {
    {"along the trajectory", "across it, where the design spreads most", "normal to both"},
    {"x", "y", "z"}};

}  // namespace

MetricsReport metamaterial_metrics(const Design& design, const MetricsOptions& options) {
  if (options.samples < 2) throw InvalidInputError("--samples", "at least 2 samples (both flexion limits)");
  const Assembly& a = design.assembly;
  MetricsReport r;
  r.name = a.name();
  r.kind = design.kind;
  r.t_star = a.t_star();
  r.t_lambda = a.flexion_interval().lower.t;
  r.t_mu = a.flexion_interval().upper.t;
  r.axes = options.axes;
  const HomogenizedStrain strain(a, options.axes);
  r.directions = strain.axes();
  r.at_t_star = sample_at(strain, a, r.t_star, nullptr);
  const std::array<std::optional<double>, 3> reference = r.at_t_star.length;
  std::vector<double> ts;
  for (std::size_t k = 0; k < options.samples; ++k) {
    ts.push_back(k + 1 == options.samples ? r.t_mu
                                          : r.t_lambda + (r.t_mu - r.t_lambda) * static_cast<double>(k) /
                                                             static_cast<double>(options.samples - 1));
  }
  ts.push_back(r.t_star);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  for (double t : ts) r.samples.push_back(t == r.t_star ? r.at_t_star : sample_at(strain, a, t, &reference));
  for (int k = 0; k < 3; ++k) {
    r.extent_deployment[k] = deployment(r.samples, [k](const MetricsSample& s) { return s.length[k]; });
    r.bounding_extent_deployment[k] =
        deployment(r.samples, [k](const MetricsSample& s) { return std::optional<double>(s.bounding_extent[k]); });
  }
  if (r.at_t_star.volume) r.volume_deployment = deployment(r.samples, [](const MetricsSample& s) { return s.volume; });
  return r;
}

const std::vector<std::string>& figure_names() {
  static const std::vector<std::string> names{"poisson.nu_12",       "poisson.nu_13",       "poisson.nu_23",
                                              "extent_deployment.0", "extent_deployment.1", "extent_deployment.2",
                                              "flexion_width",       "volume_ratio"};
  return names;
}

bool figure_needs_interval(const std::string& name) {
  return name.rfind("extent_deployment.", 0) == 0 || name == "volume_ratio";
}

std::optional<double> MetricsReport::figure(const std::string& wanted) const {
  for (int k = 0; k < 3; ++k) {
    if (wanted == figure_names()[k]) return at_t_star.poisson[k];
    if (wanted == figure_names()[3 + k]) return extent_deployment[k];
  }
  if (wanted == "flexion_width") return flexion_width();
  if (wanted == "volume_ratio") return volume_deployment;
  throw InvalidInputError("figure", "unknown figure \"" + wanted + "\"");
}

nlohmann::json MetricsReport::to_json() const {
  nlohmann::json samples_json = nlohmann::json::array();
  for (const MetricsSample& s : samples) samples_json.push_back(sample_json(s));
  nlohmann::json directions_json = nlohmann::json::array();
  for (const Vec3& d : directions) directions_json.push_back({d.x(), d.y(), d.z()});
  nlohmann::json figures = nlohmann::json::object();
  for (const std::string& f : figure_names()) figures[f] = optional_json(figure(f));
  auto optionals = [](const std::array<std::optional<double>, 3>& v) {
    return nlohmann::json{optional_json(v[0]), optional_json(v[1]), optional_json(v[2])};
  };
  return {{"name", name},
          {"kind", kind},
          {"t_star", t_star},
          {"flexion_interval", {t_lambda, t_mu}},
          {"axes", to_string(axes)},
          {"directions", directions_json},
          {"figures", figures},
          {"at_t_star", sample_json(at_t_star)},
          {"extent_deployment", optionals(extent_deployment)},
          {"bounding_extent_deployment", optionals(bounding_extent_deployment)},
          {"volume_deployment", optional_json(volume_deployment)},
          {"samples", samples_json}};
}

std::string MetricsReport::to_csv() const {
  std::ostringstream csv;
  csv << "t,length_1,length_2,length_3,bounding_extent_1,bounding_extent_2,bounding_extent_3,volume,nu_12,nu_13,nu_23";
  const std::size_t members = at_t_star.member_volume.size();
  if (members > 1) {
    for (std::size_t m = 0; m < members; ++m) csv << ",volume_member_" << m;
  }
  csv << '\n';
  for (const MetricsSample& s : samples) {
    csv << format_number(s.t);
    for (int k = 0; k < 3; ++k) csv << ',' << csv_number(s.length[k]);
    for (int k = 0; k < 3; ++k) csv << ',' << format_number(s.bounding_extent[k]);
    csv << ',' << csv_number(s.volume) << ',' << csv_number(s.poisson[0]) << ',' << csv_number(s.poisson[1]) << ','
        << csv_number(s.poisson[2]);
    if (members > 1) {
      for (const auto& v : s.member_volume) csv << ',' << csv_number(v);
    }
    csv << '\n';
  }
  return csv.str();
}

std::ostream& operator<<(std::ostream& out, const MetricsReport& r) {
  auto p = [](const std::optional<double>& v) { return v ? format_human(*v) : std::string("undefined"); };
  out << "metamaterial figures of \"" << r.name << "\" (" << r.kind << ") over [" << format_human(r.t_lambda) << ", "
      << format_human(r.t_mu) << "], " << r.samples.size() << " samples; axes " << to_string(r.axes)
      << ", fixed at t*\n";
  const int meaning = r.axes == MetricsAxes::xyz ? 1 : 0;
  for (int k = 0; k < 3; ++k) {
    out << "axis " << k + 1 << " (" << axis_meaning[meaning][k] << "): (" << format_human(r.directions[k].x()) << ", "
        << format_human(r.directions[k].y()) << ", " << format_human(r.directions[k].z()) << "), length at t* "
        << p(r.at_t_star.length[k]) << ", deployment ratio (largest / smallest) " << p(r.extent_deployment[k]) << '\n';
  }
  if (r.at_t_star.volume) {
    out << "enclosed volume at t*: " << format_human(*r.at_t_star.volume) << ", deployment ratio "
        << (r.volume_deployment ? format_human(*r.volume_deployment) : std::string("-")) << '\n';
  } else {
    out << "enclosed volume: none (no tube)\n";
  }
  out << "Poisson's ratios at t*: nu_12 " << p(r.at_t_star.poisson[0]) << ", nu_13 " << p(r.at_t_star.poisson[1])
      << ", nu_23 " << p(r.at_t_star.poisson[2]) << '\n';
  return out;
}

}  // namespace phedra
