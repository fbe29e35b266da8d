#pragma once
// Line charts a person reads at a glance, as SVG or PNG (drawn once, with
// cairo, onto either surface): stacked panels sharing the x axis, round ticks
// (plot_axes.h), a linear or logarithmic y axis, labelled series in a legend,
// marked points and vertical lines with their labels.

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace phedra {

struct ChartSeries {
  std::string label;
  std::vector<double> x;
  std::vector<std::optional<double>> y;  ///< a gap where none
  int colour = 0;                        ///< index into the palette
  bool dashed = false;
};

enum class MarkerShape { dot, triangle_up, triangle_down, diamond };

struct ChartMarker {
  double x = 0.0, y = 0.0;
  MarkerShape shape = MarkerShape::dot;
  int colour = 0;
  std::string label;  ///< drawn beside it (optional)
};

struct ChartLine {
  double x = 0.0;
  std::string label;
  bool dashed = true;
};

struct ChartPanel {
  std::string title, y_label;
  /// Its own x axis (range and label) instead of the chart's.
  std::optional<std::pair<double, double>> x_range;
  std::string x_label;
  bool log_y = false;
  std::vector<ChartSeries> series;
  std::vector<ChartMarker> markers;
  std::vector<ChartLine> lines;
  /// A marker's label in the legend, once per shape (what the shape means).
  std::vector<std::pair<MarkerShape, std::string>> marker_legend;
  std::vector<std::string> notes;  ///< short lines under the legend
};

struct Chart {
  std::string title, subtitle, x_label;
  double x_lo = 0.0, x_hi = 1.0;
  std::vector<ChartPanel> panels;
};

std::string chart_svg(const Chart& chart);
std::string chart_png(const Chart& chart);

}  // namespace phedra
