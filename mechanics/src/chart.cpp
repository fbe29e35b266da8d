#include "phedra/chart.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/plot_axes.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace phedra {
namespace {

constexpr double page_width = 960.0, panel_height = 300.0, margin_left = 92.0, margin_right = 250.0, margin_top = 78.0, panel_gap = 70.0,
                 margin_bottom = 56.0, panel_title_space = 18.0;

const double palette[][3] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74},
                             {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.50, 0.50, 0.50},
                             {0.74, 0.74, 0.13}, {0.09, 0.75, 0.81}};

void colour(cairo_t* cr, int c) {
  const double* rgb = palette[static_cast<std::size_t>(c) % (sizeof(palette) / sizeof(palette[0]))];
  cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
}

void text(cairo_t* cr, const std::string& s, double x, double y, double size, double align = 0.0, bool bold = false,
          bool vertical = false) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  if (vertical) cairo_rotate(cr, -M_PI / 2);
  cairo_move_to(cr, -align * e.x_advance, 0);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

void marker(cairo_t* cr, MarkerShape shape, double x, double y, double r) {
  cairo_new_path(cr);  // not joined to the current point (text leaves one)
  switch (shape) {
    case MarkerShape::dot: cairo_arc(cr, x, y, r, 0, 2 * M_PI); break;
    case MarkerShape::triangle_up:
      cairo_move_to(cr, x, y - 1.2 * r), cairo_line_to(cr, x + r, y + 0.8 * r), cairo_line_to(cr, x - r, y + 0.8 * r);
      break;
    case MarkerShape::triangle_down:
      cairo_move_to(cr, x, y + 1.2 * r), cairo_line_to(cr, x + r, y - 0.8 * r), cairo_line_to(cr, x - r, y - 0.8 * r);
      break;
    case MarkerShape::diamond:
      cairo_move_to(cr, x, y - 1.3 * r), cairo_line_to(cr, x + r, y), cairo_line_to(cr, x, y + 1.3 * r), cairo_line_to(cr, x - r, y);
      break;
  }
  cairo_close_path(cr);
}

/// Exponent labels of a log axis: "1e-3" for people, or the round value when it reads better.
std::string power_label(int p) {
  if (p >= -2 && p <= 3) return format_number(std::pow(10.0, p));
  return "1e" + std::to_string(p);
}

void draw_panel(cairo_t* cr, const Chart& chart, const ChartPanel& panel, double y0, bool axis_label) {
  const double w = page_width - margin_left - margin_right, h = panel_height;
  const double x_lo = panel.x_range ? panel.x_range->first : chart.x_lo;
  const double x_hi = panel.x_range ? panel.x_range->second : chart.x_hi;
  auto sx = [&](double x) { return margin_left + (x - x_lo) / (x_hi - x_lo) * w; };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto take = [&](double v) {
    if (!std::isfinite(v) || (panel.log_y && !(v > 0.0))) return;
    lo = std::min(lo, v), hi = std::max(hi, v);
  };
  for (const ChartSeries& s : panel.series)
    for (const auto& v : s.y)
      if (v) take(*v);
  for (const ChartMarker& m : panel.markers) take(m.y);
  if (!(hi >= lo)) lo = panel.log_y ? 1.0 : 0.0, hi = panel.log_y ? 10.0 : 1.0;
  std::vector<std::pair<double, std::string>> ticks;
  double ylo, yhi;
  if (panel.log_y) {
    int a = static_cast<int>(std::floor(std::log10(lo))), b = static_cast<int>(std::ceil(std::log10(hi)));
    if (a == b) --a, ++b;
    const int step = std::max(1, (b - a + 5) / 6);
    for (int p = a; p <= b; p += step) {
      ticks.push_back({static_cast<double>(p), power_label(p)});
      if (b - a > 2 || p == b) continue;
      for (double m : {2.0, 5.0}) ticks.push_back({p + std::log10(m), format_significant(m * std::pow(10.0, p), 3)});
    }
    ylo = a, yhi = b;
  } else {
    if (hi - lo <= 1e-300 + 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
      const double pad = std::max(1e-12, 0.5 * std::abs(hi));
      lo -= pad, hi += pad;
    }
    std::tie(ylo, yhi) = round_range(lo, hi);
    const Ticks t = round_ticks(ylo, yhi);
    for (std::size_t i = 0; i < t.values.size(); ++i) ticks.push_back({t.values[i], t.labels[i]});
  }
  auto sy = [&](double v) {
    const double u = panel.log_y ? std::log10(v) : v;
    return y0 + h - (u - ylo) / (yhi - ylo) * h;
  };
  // Frame, grid, ticks.
  cairo_set_line_width(cr, 1.0);
  cairo_set_source_rgb(cr, 0.92, 0.92, 0.92);
  for (const auto& [v, label] : ticks) {
    const double y = y0 + h - (v - ylo) / (yhi - ylo) * h;
    cairo_move_to(cr, margin_left, y), cairo_line_to(cr, margin_left + w, y);
  }
  const Ticks xt = round_ticks(x_lo, x_hi, 8);
  for (double v : xt.values) cairo_move_to(cr, sx(v), y0), cairo_line_to(cr, sx(v), y0 + h);
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_rectangle(cr, margin_left, y0, w, h);
  cairo_stroke(cr);
  for (const auto& [v, label] : ticks) text(cr, label, margin_left - 8, y0 + h - (v - ylo) / (yhi - ylo) * h + 4, 12, 1.0);
  for (std::size_t i = 0; i < xt.values.size(); ++i) text(cr, xt.labels[i], sx(xt.values[i]), y0 + h + 17, 12, 0.5);
  if (panel.x_range) {
    text(cr, panel.x_label, margin_left + w / 2, y0 + h + 38, 13, 0.5);
  } else if (axis_label) {
    text(cr, chart.x_label, margin_left + w / 2, y0 + h + 38, 13, 0.5);
  }
  text(cr, panel.title, margin_left, y0 - 10, 14, 0.0, true);
  text(cr, panel.y_label, margin_left - 62, y0 + h / 2, 13, 0.5, false, true);
  // Vertical lines.
  cairo_save(cr);
  cairo_rectangle(cr, margin_left, y0, w, h);
  cairo_clip(cr);
  for (const ChartLine& l : panel.lines) {
    cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
    const double dash[] = {5, 4};
    cairo_set_dash(cr, dash, l.dashed ? 2 : 0, 0);
    cairo_move_to(cr, sx(l.x), y0), cairo_line_to(cr, sx(l.x), y0 + h);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    text(cr, l.label, sx(l.x) + 4, y0 + 14, 11);
  }
  // Series.
  cairo_set_line_width(cr, 2.0);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const ChartSeries& s : panel.series) {
    colour(cr, s.colour);
    const double dash[] = {7, 4};
    cairo_set_dash(cr, dash, s.dashed ? 2 : 0, 0);
    bool open = false;
    std::size_t run = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const bool ok = s.y[i] && std::isfinite(*s.y[i]) && (!panel.log_y || *s.y[i] > 0.0);
      if (!ok) {
        if (open && run == 1) cairo_rel_line_to(cr, 0.01, 0);  // a lone point still shows
        open = false;
        continue;
      }
      (open ? cairo_line_to : cairo_move_to)(cr, sx(s.x[i]), sy(*s.y[i]));
      run = open ? run + 1 : 1;
      open = true;
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  int labelled = 0;
  for (const ChartMarker& m : panel.markers) {
    if (panel.log_y && !(m.y > 0.0)) continue;
    marker(cr, m.shape, sx(m.x), sy(m.y), 6);
    colour(cr, m.colour);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    if (!m.label.empty()) text(cr, m.label, sx(m.x) + 9, sy(m.y) + (labelled++ % 2 ? 18 : -9), 11);
  }
  cairo_restore(cr);
  // Legend on the right.
  double ly = y0 + 8;
  const double lx = margin_left + w + 18;
  for (const ChartSeries& s : panel.series) {
    if (s.label.empty()) continue;
    colour(cr, s.colour);
    cairo_set_line_width(cr, 2.5);
    const double dash[] = {7, 4};
    cairo_set_dash(cr, dash, s.dashed ? 2 : 0, 0);
    cairo_move_to(cr, lx, ly), cairo_line_to(cr, lx + 26, ly);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, s.label, lx + 32, ly + 4, 12);
    ly += 20;
  }
  for (const std::string& note : panel.notes) {
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    text(cr, note, lx, ly + 4, 11);
    ly += 18;
  }
  for (const auto& [shape, label] : panel.marker_legend) {
    marker(cr, shape, lx + 13, ly, 6);
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    text(cr, label, lx + 32, ly + 4, 12);
    ly += 20;
  }
}

double chart_height(const Chart& chart) {
  // Each panel's frame starts panel_title_space below its slot (draw_chart): without
  // it the last x label's baseline sat on the page's edge, its descenders cut off.
  return margin_top + panel_title_space + static_cast<double>(chart.panels.size()) * (panel_height + panel_gap) -
         panel_gap + margin_bottom;
}

void draw(cairo_t* cr, const Chart& chart) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
  text(cr, chart.title, margin_left, 30, 17, 0.0, true);
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  text(cr, chart.subtitle, margin_left, 52, 12.5);
  // The chart's x label under the last panel on the chart's own axis (the energy's
  // force panel below it has an axis of its own: the label had gone with it).
  std::size_t labelled = chart.panels.size();
  for (std::size_t p = 0; p < chart.panels.size(); ++p) {
    if (!chart.panels[p].x_range) labelled = p;
  }
  for (std::size_t p = 0; p < chart.panels.size(); ++p) {
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_panel(cr, chart, chart.panels[p], margin_top + static_cast<double>(p) * (panel_height + panel_gap) + panel_title_space,
               p == labelled);
  }
}

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void check(cairo_status_t status) {
  if (status != CAIRO_STATUS_SUCCESS) throw Error(ExitCode::internal, std::string("chart: ") + cairo_status_to_string(status));
}

}  // namespace

std::string chart_svg(const Chart& chart) {
  std::string out;
  cairo_surface_t* surface = cairo_svg_surface_create_for_stream(append, &out, page_width, chart_height(chart));
  cairo_t* cr = cairo_create(surface);
  draw(cr, chart);
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  cairo_surface_destroy(surface);
  check(status);
  return out;
}

std::string chart_png(const Chart& chart) {
  const double scale = 1.5;  // crisp at the size people look at it
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(page_width * scale),
                                                        static_cast<int>(chart_height(chart) * scale));
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, scale, scale);
  draw(cr, chart);
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  std::string out;
  const cairo_status_t written = cairo_surface_write_to_png_stream(surface, append, &out);
  cairo_surface_destroy(surface);
  check(status);
  check(written);
  return out;
}

}  // namespace phedra
