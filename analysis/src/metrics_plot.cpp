// The metrics' SVG plots (MetricsReport::to_svg): lengths and volume relative
// to t*, and Poisson's ratios, against t.

#include "phedra/metamaterial_metrics.h"
#include "phedra/plot_axes.h"

#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace phedra {
namespace {

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

/// The symmetric log scale of the Poisson plot: linear within +-1, a decade a
/// unit beyond (+-10 at +-2, +-100 at +-3), so that a ratio near a pole and one
/// near 0 are both on the scale.
double symlog(double v) { return std::abs(v) <= 1.0 ? v : std::copysign(1.0 + std::log10(std::abs(v)), v); }

/// The value at a symlog position (for tick labels).
double symlog_inverse(double f) { return std::abs(f) <= 1.0 ? f : std::copysign(std::pow(10.0, std::abs(f) - 1.0), f); }

/// Where L_j is stationary (d ln L_j / dt changes sign between two samples): the
/// poles of nu_jk, by linear interpolation of the rate.
std::vector<std::pair<int, double>> stationary_lengths(const MetricsReport& r) {
  std::vector<std::pair<int, double>> out;
  for (int j = 0; j < 2; ++j) {  // L1 (nu_12, nu_13) and L2 (nu_23)
    for (std::size_t k = 0; k + 1 < r.samples.size(); ++k) {
      const auto& a = r.samples[k].strain_rate[j];
      const auto& b = r.samples[k + 1].strain_rate[j];
      if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b) || !(*a * *b < 0.0)) continue;
      const double ta = r.samples[k].t, tb = r.samples[k + 1].t;
      out.push_back({j, ta + (tb - ta) * *a / (*a - *b)});
    }
  }
  return out;
}

void plot(std::ostringstream& svg, const MetricsReport& r, double x, double y, double w, double h,
          const std::string& title, const std::string& y_label, const Series& series, std::optional<double> clip,
          bool log_scale = false, const std::vector<int>& pole_of = {}) {
  static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
  // The axis's coordinate of a value (the symmetric log with log_scale).
  auto scale = [&](double v) { return log_scale ? symlog(v) : v; };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  bool clipped = false;
  for (const auto& [name, values] : series) {
    for (const auto& v : values) {
      if (!v) continue;
      clipped = clipped || (clip && std::abs(*v) > *clip);
      const double c = scale(clip ? std::clamp(*v, -*clip, *clip) : *v);
      lo = std::min(lo, c), hi = std::max(hi, c);
    }
  }
  if (!(hi >= lo)) lo = 0.0, hi = 1.0;
  if (log_scale) {
    lo = std::min(std::floor(lo), -1.0), hi = std::max(std::ceil(hi), 1.0);  // whole decades, +-1 at least
  } else {
    std::tie(lo, hi) = round_range(lo, hi);
    if (clip) lo = std::max(lo, -*clip), hi = std::min(hi, *clip);
  }
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
  Ticks yt;
  if (log_scale) {
    // A tick a decade (+-1, +-10, +-100, ...) and at 0 and +-0.5 in the linear part.
    // +-0.5 only while the axis has room (a few decades).
    for (double f = lo; f <= hi + 1e-9; f += 0.5) {
      if (f != std::round(f) && (std::abs(f) > 1.0 || hi - lo > 6.0)) continue;
      const double v = symlog_inverse(f);
      const int decade = static_cast<int>(std::lround(std::abs(f))) - 1;
      yt.values.push_back(f);
      yt.labels.push_back(std::abs(f) < 1e-9 ? "0"
                          : std::abs(v) >= 1e3 ? std::string(v < 0 ? "-" : "") + "1e" + std::to_string(decade)
                                               : format_significant(v, 3));
    }
  } else {
    yt = round_ticks(lo, hi);
  }
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
  // Poles: where a length is stationary its Poisson's ratios pass through infinity.
  const std::vector<std::pair<int, double>> poles = pole_of.empty() ? std::vector<std::pair<int, double>>{}
                                                                    : stationary_lengths(r);
  // Each line's label beside it, inside the plot (left of a line near the right edge), on the
  // lowest row along the bottom where it overlaps no other label.
  const double label_width = 72.0;  // "L1 stationary" at 10 px
  std::vector<std::vector<std::pair<double, double>>> rows;  // labels' extents, by row
  std::string pole_labels;
  for (const auto& [j, t] : poles) {
    const double u = sx(t);
    const bool left = u + 3 + label_width > x + w;
    const double from = left ? u - 3 - label_width : u + 3, to = from + label_width;
    std::size_t row = 0;
    for (; row < rows.size(); ++row) {
      const bool free = std::none_of(rows[row].begin(), rows[row].end(), [&](const auto& e) {
        return from < e.second + 4 && to > e.first - 4;
      });
      if (free) break;
    }
    if (row == rows.size()) rows.emplace_back();
    rows[row].push_back({from, to});
    svg << "<line class=\"pole\" x1=\"" << px(u) << "\" y1=\"" << px(y) << "\" x2=\"" << px(u) << "\" y2=\""
        << px(y + h) << "\" stroke=\"#555\" stroke-dasharray=\"2 3\"/>\n";
    // Drawn after the curves, on a white halo, so that no curve hides a letter.
    pole_labels += "<text class=\"pole-label\" x=\"" + px(left ? u - 3 : u + 3) + "\" y=\"" +
                   px(y + h - 4 - 12.0 * static_cast<double>(row)) + "\" text-anchor=\"" + (left ? "end" : "start") +
                   "\" fill=\"#555\" font-size=\"10\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">L" +
                   std::to_string(j + 1) + " stationary</text>\n";
  }
  auto crosses_pole = [&](std::size_t s, double ta, double tb) {
    if (s >= pole_of.size()) return false;
    for (const auto& [j, t] : poles) {
      if (j == pole_of[s] && t > ta && t < tb) return true;
    }
    return false;
  };
  double legend_y = y + 14;
  bool limit_values = false;
  for (std::size_t s = 0; s < series.size(); ++s) {
    const auto& [name, values] = series[s];
    std::string points, markers;
    std::optional<double> last;
    std::optional<double> last_t;
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
      const double v = scale(clip ? std::clamp(*values[k], -*clip, *clip) : *values[k]);
      if (log_scale && (k == 0 || k + 1 == values.size())) {
        // The value at a flexion limit: a limit (the motion is singular there), not joined to its neighbour.
        markers += "<circle class=\"limit-value\" cx=\"" + px(sx(r.samples[k].t)) + "\" cy=\"" + px(sy(v)) +
                   "\" r=\"3\" fill=\"white\" stroke=\"" + std::string(colours[s % 5]) + "\" stroke-width=\"1.5\"/>";
        limit_values = true;
        flush();
        last.reset();
        continue;
      }
      // A jump across most of the axis (a ratio through infinity) is not joined by a line, nor is a pole crossed.
      if (last && (std::abs(v - *last) > 0.6 * (hi - lo) || (last_t && crosses_pole(s, *last_t, r.samples[k].t)))) flush();
      last = v;
      last_t = r.samples[k].t;
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
  svg << pole_labels;
  if (limit_values) {
    svg << "<circle cx=\"" << px(x + w + 19) << "\" cy=\"" << px(legend_y - 4) << "\" r=\"3\" fill=\"white\" stroke=\"#444\" "
           "stroke-width=\"1.5\"/><text class=\"limit-note\" x=\"" << px(x + w + 32) << "\" y=\"" << px(legend_y)
        << "\">at a flexion limit</text>\n";
    legend_y += 16;
  }
  if (log_scale) {
    svg << "<text class=\"scale-note\" x=\"" << px(x + w + 10) << "\" y=\"" << px(legend_y + 4)
        << "\" fill=\"#444\">linear within &#177;1,</text><text x=\"" << px(x + w + 10) << "\" y=\"" << px(legend_y + 18)
        << "\" fill=\"#444\">a decade a step beyond</text>\n";
    legend_y += 32;
  }
  if (clipped) {
    svg << "<text class=\"clip-note\" x=\"" << px(x + w + 10) << "\" y=\"" << px(legend_y + 4)
        << "\" fill=\"#444\">beyond &#177;" << format_number(*clip) << ": clipped,</text><text x=\"" << px(x + w + 10)
        << "\" y=\"" << px(legend_y + 18) << "\" fill=\"#444\">marked &#9650; &#9660; at the edge</text>\n";
  }
  svg << "</g>\n";
}

}  // namespace

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
      ratios[k].second.push_back(s.length[k] && at_t_star.length[k] ? finite_or_none(*s.length[k] / *at_t_star.length[k])
                                                                    : std::nullopt);
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
  const std::string extents_title = volume_drawn ? "Lengths along the axes (homogenized stretch) and enclosed volume"
                                    : at_t_star.volume ? "Lengths along the axes (enclosed volume 0 at t*: no ratio to it)"
                                                       : "Lengths along the axes (homogenized stretch)";
  plot(svg, *this, 90, 90, 560, 220, extents_title,
       "ratio to the value at t* (dimensionless)", ratios, std::nullopt);
  plot(svg, *this, 90, 440, 560, 220, "Effective Poisson's ratios nu_jk = -(d ln L_k) / (d ln L_j)",
       "Poisson's ratio (dimensionless, symmetric log)", poisson, poisson_clip, true, {0, 0, 1});
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace phedra
