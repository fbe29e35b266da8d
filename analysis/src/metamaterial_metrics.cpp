#include "phedra/metamaterial_metrics.h"
#include "phedra/plot_axes.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>

namespace phedra {
namespace {

/// The principal directions of the points, largest spread first.
std::array<Vec3, 3> principal_directions(const std::vector<Points>& members) {
  Vec3 mean = Vec3::Zero();
  std::size_t count = 0;
  for (const Points& m : members) {
    for (const Vec3& p : m) mean += p;
    count += m.size();
  }
  mean /= static_cast<double>(count);
  Mat3 covariance = Mat3::Zero();
  for (const Points& m : members) {
    for (const Vec3& p : m) covariance += (p - mean) * (p - mean).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);  // ascending eigenvalues
  std::array<Vec3, 3> d{solver.eigenvectors().col(2), solver.eigenvectors().col(1), solver.eigenvectors().col(0)};
  // A sign convention, so that reports do not flip between runs: largest component positive.
  for (Vec3& v : d) {
    Eigen::Index k;
    v.cwiseAbs().maxCoeff(&k);
    if (v[k] < 0.0) v = -v;
  }
  return d;
}

std::array<double, 3> extents(const std::vector<Points>& members, const std::array<Vec3, 3>& d) {
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

class Evaluator {
 public:
  explicit Evaluator(const Design& design) : a_(design.assembly) {}
  const std::vector<Points>& at(double t) {
    a_.evaluate(t, configuration_);
    return configuration_.members;
  }

 private:
  const Assembly& a_;
  AssemblyConfiguration configuration_;
};

MetricsSample sample_at(Evaluator& evaluator, const Assembly& a, const std::array<Vec3, 3>& d, double t) {
  MetricsSample s;
  s.t = t;
  const std::vector<Points>& members = evaluator.at(t);
  s.extent = extents(members, d);
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
  // Poisson's ratios from the derivatives of the extents (central differences).
  const double lo = a.flexion_interval().lower.t, hi = a.flexion_interval().upper.t, width = hi - lo;
  const double h = 1e-6 * width;
  const double t0 = std::max(lo, t - h), t1 = std::min(hi, t + h);
  const std::array<double, 3> e0 = extents(evaluator.at(t0), d), e1 = extents(evaluator.at(t1), d);
  std::array<double, 3> strain_rate{};  // d(ln L)/dt
  for (int k = 0; k < 3; ++k) strain_rate[k] = (e1[k] - e0[k]) / (t1 - t0) / s.extent[k];
  const std::array<std::pair<int, int>, 3> pairs{{{0, 1}, {0, 2}, {1, 2}}};
  for (int p = 0; p < 3; ++p) {
    const auto [j, k] = pairs[p];
    if (std::abs(strain_rate[j]) * width > 1e-7 && std::isfinite(strain_rate[k] / strain_rate[j])) {
      s.poisson[p] = -strain_rate[k] / strain_rate[j];
    }
  }
  return s;
}

nlohmann::json optional_json(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::json sample_json(const MetricsSample& s) {
  nlohmann::json members = nlohmann::json::array();
  for (const auto& v : s.member_volume) members.push_back(optional_json(v));
  return {{"t", s.t},
          {"extent", s.extent},
          {"volume", optional_json(s.volume)},
          {"member_volume", members},
          {"poisson", {{"nu_12", optional_json(s.poisson[0])},
                       {"nu_13", optional_json(s.poisson[1])},
                       {"nu_23", optional_json(s.poisson[2])}}}};
}

std::string csv_number(const std::optional<double>& v) { return v ? format_number(*v) : std::string(); }

using Series = std::vector<std::pair<std::string, std::vector<std::optional<double>>>>;

/// A pixel coordinate: two decimals are finer than any screen.
std::string px(double v) { return format_number(std::round(v * 100.0) / 100.0); }

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

/// One plot of `series` against t in the box (x, y, w, h): round ticks on both
/// axes, t's unit below, the share of the flexion interval above, t* marked,
/// the parts of the motion that are not buildable shaded. With `clip`, values
/// beyond +-clip are drawn at the edge with a marker and the axis stops there.
/// A plotted value, or none when it is not a number (a ratio to a zero).
std::optional<double> finite_or_none(double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; }

void plot(std::ostringstream& svg, const MetricsReport& r, double x, double y, double w, double h,
          const std::string& title, const std::string& y_label, const Series& series, std::optional<double> clip) {
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  bool clipped = false;
  for (const auto& [name, values] : series) {
    for (const auto& v : values) {
      if (!v) continue;
      clipped = clipped || (clip && std::abs(*v) > *clip);
      const double c = clip ? std::clamp(*v, -*clip, *clip) : *v;
      lo = std::min(lo, c), hi = std::max(hi, c);
    }
  }
  if (!(hi >= lo)) lo = 0.0, hi = 1.0;
  std::tie(lo, hi) = round_range(lo, hi);
  if (clip) lo = std::max(lo, -*clip), hi = std::min(hi, *clip);
  auto sx = [&](double t) { return x + (t - r.t_lambda) / (r.t_mu - r.t_lambda) * w; };
  auto sy = [&](double v) { return y + h - (v - lo) / (hi - lo) * h; };
  svg << "<g font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"11\">\n";
  svg << "<text x=\"" << px(x) << "\" y=\"" << px(y - 26) << "\" font-size=\"13\" font-weight=\"bold\">" << escape(title)
      << "</text>\n";
  // Not buildable: shaded.
  if (r.buildability_known) {
    std::vector<std::pair<double, double>> bad;
    if (!r.buildable) {
      bad.push_back({r.t_lambda, r.t_mu});
    } else {
      if (r.buildable->first > r.t_lambda) bad.push_back({r.t_lambda, r.buildable->first});
      if (r.buildable->second < r.t_mu) bad.push_back({r.buildable->second, r.t_mu});
    }
    for (const auto& [a, b] : bad) {
      svg << "<rect class=\"not-buildable\" x=\"" << px(sx(a)) << "\" y=\"" << px(y) << "\" width=\"" << px(sx(b) - sx(a))
          << "\" height=\"" << px(h) << "\" fill=\"#f6c9c9\"/>\n";
    }
  }
  // y: gridlines at round values, labelled on the left; the quantity rotated beside them.
  const Ticks yt = round_ticks(lo, hi);
  std::size_t widest = 0;
  for (const std::string& label : yt.labels) widest = std::max(widest, label.size());
  for (std::size_t k = 0; k < yt.values.size(); ++k) {
    const double v = sy(yt.values[k]);
    svg << "<line x1=\"" << px(x) << "\" y1=\"" << px(v) << "\" x2=\"" << px(x + w) << "\" y2=\"" << px(v)
        << "\" stroke=\"#e2e2e2\"/><text class=\"y-tick\" x=\"" << px(x - 5) << "\" y=\"" << px(v + 4)
        << "\" text-anchor=\"end\">" << yt.labels[k] << "</text>\n";
  }
  svg << "<text class=\"y-label\" transform=\"translate(" << px(x - 16 - 6.5 * static_cast<double>(widest)) << ' ' << px(y + h / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">" << escape(y_label) << "</text>\n";
  // t below, at round values; the share of the flexion interval above.
  const Ticks xt = round_ticks(r.t_lambda, r.t_mu, 6);
  for (std::size_t k = 0; k < xt.values.size(); ++k) {
    const double u = sx(xt.values[k]);
    svg << "<line x1=\"" << px(u) << "\" y1=\"" << px(y + h) << "\" x2=\"" << px(u) << "\" y2=\"" << px(y + h + 4)
        << "\" stroke=\"#888\"/><text class=\"x-tick\" x=\"" << px(u) << "\" y=\"" << px(y + h + 16)
        << "\" text-anchor=\"middle\">" << xt.labels[k] << "</text>\n";
  }
  svg << "<text class=\"x-label\" x=\"" << px(x + w / 2) << "\" y=\"" << px(y + h + 32)
      << "\" text-anchor=\"middle\">t: height of the moving apex (model units); flexion interval [" << format_significant(r.t_lambda)
      << ", " << format_significant(r.t_mu) << "]</text>\n";
  for (int k = 0; k <= 4; ++k) {
    const double u = x + w * k / 4.0;
    svg << "<line x1=\"" << px(u) << "\" y1=\"" << px(y - 4) << "\" x2=\"" << px(u) << "\" y2=\"" << px(y)
        << "\" stroke=\"#888\"/><text class=\"fraction-tick\" x=\"" << px(u) << "\" y=\"" << px(y - 7)
        << "\" text-anchor=\"middle\" fill=\"#666\">" << 25 * k << " %</text>\n";
  }
  svg << "<text x=\"" << px(x + w + 24) << "\" y=\"" << px(y - 7) << "\" fill=\"#666\">of the interval</text>\n";
  svg << "<rect x=\"" << px(x) << "\" y=\"" << px(y) << "\" width=\"" << px(w) << "\" height=\"" << px(h)
      << "\" fill=\"none\" stroke=\"#888\"/>\n";
  svg << "<line x1=\"" << px(sx(r.t_star)) << "\" y1=\"" << px(y) << "\" x2=\"" << px(sx(r.t_star)) << "\" y2=\""
      << px(y + h) << "\" stroke=\"#999\" stroke-dasharray=\"4 3\"/><text x=\"" << px(sx(r.t_star) + 3) << "\" y=\""
      << px(y + 12) << "\" fill=\"#777\">t*</text>\n";
  double legend_y = y + 14;
  for (std::size_t s = 0; s < series.size(); ++s) {
    const auto& [name, values] = series[s];
    std::string points, markers;
    std::optional<double> last;
    auto flush = [&] {
      if (!points.empty()) {
        svg << "<polyline fill=\"none\" stroke-width=\"1.5\" stroke=\"" << colours[s % 5] << "\" points=\"" << points
            << "\"/>";
      }
      points.clear();
    };
    for (std::size_t k = 0; k < values.size(); ++k) {
      if (!values[k]) {
        flush();  // undefined here: the line breaks
        last.reset();
        continue;
      }
      const double v = clip ? std::clamp(*values[k], -*clip, *clip) : *values[k];
      // A jump across most of the axis (a ratio through infinity) is not joined by a line.
      if (last && std::abs(v - *last) > 0.6 * (hi - lo)) flush();
      last = v;
      points += px(sx(r.samples[k].t)) + "," + px(sy(v)) + " ";
      if (clip && std::abs(*values[k]) > *clip) {
        const double u = sx(r.samples[k].t), e = sy(v), d = *values[k] > 0 ? -5.0 : 5.0;
        markers += "<polygon class=\"clipped\" fill=\"" + std::string(colours[s % 5]) + "\" points=\"" + px(u - 3) + "," +
                   px(e) + " " + px(u + 3) + "," + px(e) + " " + px(u) + "," + px(e + d) + "\"/>";
      }
    }
    flush();
    svg << markers << "\n";
    svg << "<line x1=\"" << px(x + w + 10) << "\" y1=\"" << px(legend_y - 4) << "\" x2=\"" << px(x + w + 28) << "\" y2=\""
        << px(legend_y - 4) << "\" stroke-width=\"2\" stroke=\"" << colours[s % 5] << "\"/><text x=\"" << px(x + w + 32)
        << "\" y=\"" << px(legend_y) << "\">" << escape(name) << "</text>\n";
    legend_y += 16;
  }
  if (r.buildability_known && (!r.buildable || r.buildable->first > r.t_lambda || r.buildable->second < r.t_mu)) {
    svg << "<rect x=\"" << px(x + w + 10) << "\" y=\"" << px(legend_y - 10) << "\" width=\"18\" height=\"10\" fill=\"#f6c9c9\"/>"
        << "<text x=\"" << px(x + w + 32) << "\" y=\"" << px(legend_y) << "\">not buildable</text>\n";
    legend_y += 16;
  }
  if (clipped) {
    svg << "<text class=\"clip-note\" x=\"" << px(x + w + 10) << "\" y=\"" << px(legend_y + 4)
        << "\" fill=\"#444\">beyond &#177;" << format_number(*clip) << ": clipped,</text><text x=\"" << px(x + w + 10)
        << "\" y=\"" << px(legend_y + 18) << "\" fill=\"#444\">marked &#9650; &#9660; at the edge</text>\n";
  }
  svg << "</g>\n";
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

MetricsReport metamaterial_metrics(const Design& design, const MetricsOptions& options) {
  if (options.samples < 2) throw InvalidInputError("--samples", "at least 2 samples (both flexion limits)");
  const Assembly& a = design.assembly;
  MetricsReport r;
  r.name = a.name();
  r.kind = design.kind;
  r.t_star = a.t_star();
  r.t_lambda = a.flexion_interval().lower.t;
  r.t_mu = a.flexion_interval().upper.t;
  Evaluator evaluator(design);
  r.directions = principal_directions(evaluator.at(r.t_star));
  std::vector<double> ts;
  for (std::size_t k = 0; k < options.samples; ++k) {
    ts.push_back(k + 1 == options.samples ? r.t_mu
                                          : r.t_lambda + (r.t_mu - r.t_lambda) * static_cast<double>(k) /
                                                             static_cast<double>(options.samples - 1));
  }
  ts.push_back(r.t_star);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  for (double t : ts) r.samples.push_back(sample_at(evaluator, a, r.directions, t));
  r.at_t_star = *std::find_if(r.samples.begin(), r.samples.end(), [&](const MetricsSample& s) { return s.t == r.t_star; });
  for (int k = 0; k < 3; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const MetricsSample& s : r.samples) {
      lo = std::min(lo, s.extent[k]);
      hi = std::max(hi, s.extent[k]);
    }
    r.extent_deployment[k] = lo > 0.0 ? hi / lo : 0.0;
  }
  if (r.at_t_star.volume) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const MetricsSample& s : r.samples) {
      lo = std::min(lo, *s.volume);
      hi = std::max(hi, *s.volume);
    }
    if (lo > 0.0) r.volume_deployment = hi / lo;
  }
  return r;
}

nlohmann::json MetricsReport::to_json() const {
  nlohmann::json samples_json = nlohmann::json::array();
  for (const MetricsSample& s : samples) samples_json.push_back(sample_json(s));
  nlohmann::json directions_json = nlohmann::json::array();
  for (const Vec3& d : directions) directions_json.push_back({d.x(), d.y(), d.z()});
  return {{"name", name},
          {"kind", kind},
          {"t_star", t_star},
          {"flexion_interval", {t_lambda, t_mu}},
          {"principal_directions", directions_json},
          {"at_t_star", sample_json(at_t_star)},
          {"extent_deployment", extent_deployment},
          {"volume_deployment", optional_json(volume_deployment)},
          {"samples", samples_json}};
}

std::string MetricsReport::to_csv() const {
  std::ostringstream csv;
  csv << "t,extent_1,extent_2,extent_3,volume,nu_12,nu_13,nu_23";
  const std::size_t members = at_t_star.member_volume.size();
  if (members > 1) {
    for (std::size_t m = 0; m < members; ++m) csv << ",volume_member_" << m;
  }
  csv << '\n';
  for (const MetricsSample& s : samples) {
    csv << format_number(s.t) << ',' << format_number(s.extent[0]) << ',' << format_number(s.extent[1]) << ','
        << format_number(s.extent[2]) << ',' << csv_number(s.volume) << ',' << csv_number(s.poisson[0]) << ','
        << csv_number(s.poisson[1]) << ',' << csv_number(s.poisson[2]);
    if (members > 1) {
      for (const auto& v : s.member_volume) csv << ',' << csv_number(v);
    }
    csv << '\n';
  }
  return csv.str();
}

std::string MetricsReport::to_svg() const {
  std::ostringstream svg;
  const double width = 860, height = 720;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n<title>" << escape(name) << ": metamaterial figures against t"
      << "</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"20\" y=\"26\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"16\" "
         "font-weight=\"bold\">" << escape(name) << " (" << escape(kind) << "): figures against t</text>\n";
  Series ratios(3), poisson(3);
  const char* extent_names[] = {"L1 / L1(t*)", "L2 / L2(t*)", "L3 / L3(t*)"};
  const char* poisson_names[] = {"nu_12", "nu_13", "nu_23"};
  for (int k = 0; k < 3; ++k) {
    ratios[k].first = extent_names[k];
    poisson[k].first = poisson_names[k];
    for (const MetricsSample& s : samples) {
      ratios[k].second.push_back(finite_or_none(s.extent[k] / at_t_star.extent[k]));
      poisson[k].second.push_back(s.poisson[k] ? finite_or_none(*s.poisson[k]) : std::nullopt);
    }
  }
  // A volume of 0 at t* (a tube folded flat there) has no ratio: left out, never NaN in the file.
  if (at_t_star.volume && *at_t_star.volume != 0.0 && std::isfinite(*at_t_star.volume)) {
    ratios.push_back({"V / V(t*)", {}});
    for (const MetricsSample& s : samples) ratios.back().second.push_back(finite_or_none(*s.volume / *at_t_star.volume));
  }
  // A tube with no volume at t* has no volume ratio: the title says so rather than leave the reader looking for it.
  const bool volume_drawn = ratios.size() > 3;
  const std::string extents_title = volume_drawn ? "Extents along the principal directions and enclosed volume"
                                    : at_t_star.volume ? "Extents along the principal directions (enclosed volume 0 at t*: no ratio to it)"
                                                       : "Extents along the principal directions";
  plot(svg, *this, 90, 90, 560, 220, extents_title,
       "ratio to the value at t* (dimensionless)", ratios, std::nullopt);
  plot(svg, *this, 90, 440, 560, 220, "Effective Poisson's ratios nu_jk = -(dL_k/L_k) / (dL_j/L_j)",
       "Poisson's ratio (dimensionless)", poisson, poisson_clip);
  svg << "</svg>\n";
  return svg.str();
}

std::ostream& operator<<(std::ostream& out, const MetricsReport& r) {
  out << "metamaterial figures of \"" << r.name << "\" (" << r.kind << ") over [" << format_human(r.t_lambda) << ", "
      << format_human(r.t_mu) << "], " << r.samples.size() << " samples\n";
  for (int k = 0; k < 3; ++k) {
    out << "direction " << k + 1 << ": (" << format_human(r.directions[k].x()) << ", "
        << format_human(r.directions[k].y()) << ", " << format_human(r.directions[k].z()) << "), extent at t* "
        << format_human(r.at_t_star.extent[k]) << ", deployment ratio (largest / smallest) "
        << format_human(r.extent_deployment[k]) << '\n';
  }
  if (r.at_t_star.volume) {
    out << "enclosed volume at t*: " << format_human(*r.at_t_star.volume) << ", deployment ratio "
        << (r.volume_deployment ? format_human(*r.volume_deployment) : std::string("-")) << '\n';
  } else {
    out << "enclosed volume: none (no tube)\n";
  }
  auto p = [](const std::optional<double>& v) { return v ? format_human(*v) : std::string("undefined"); };
  out << "Poisson's ratios at t*: nu_12 " << p(r.at_t_star.poisson[0]) << ", nu_13 " << p(r.at_t_star.poisson[1])
      << ", nu_23 " << p(r.at_t_star.poisson[2]) << '\n';
  return out;
}

}  // namespace phedra
