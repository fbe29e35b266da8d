// Cut sheets as SVG (one file per page, in mm) and DXF (every page side by side).

#include "phedra/cut_sheets.h"

#include "phedra/number_format.h"

#include <cmath>
#include <sstream>

namespace phedra {
namespace {

std::string n(double x) {
  // Sheets are in mm: a thousandth of a millimetre is finer than any cutter.
  const double r = std::round(x * 1e4) / 1e4;
  return format_number(r == 0.0 ? 0.0 : r);
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      default: out += c;
    }
  }
  return out;
}

const char* svg_style(LineStyle style) {
  switch (style) {
    case LineStyle::cut: return "stroke=\"#000\" stroke-width=\"0.25\"";
    case LineStyle::mountain: return "stroke=\"#c62828\" stroke-width=\"0.3\" stroke-dasharray=\"3 1 0.6 1\"";
    case LineStyle::valley: return "stroke=\"#1e5bb8\" stroke-width=\"0.3\" stroke-dasharray=\"2 1\"";
    case LineStyle::flat: return "stroke=\"#2e7d32\" stroke-width=\"0.25\" stroke-dasharray=\"1 1\"";
    case LineStyle::tab_fold: return "stroke=\"#777\" stroke-width=\"0.25\" stroke-dasharray=\"0.6 0.8\"";
    case LineStyle::frame: return "stroke=\"#ccc\" stroke-width=\"0.2\"";
  }
  return "";
}

const char* svg_fill(FillStyle style) {
  switch (style) {
    case FillStyle::tab:
    case FillStyle::swatch_tab: return "#e4e4e4";
    case FillStyle::not_cuttable:
    case FillStyle::swatch_not_cuttable: return "#f4a6a6";
  }
  return "none";
}

const char* text_colour(TextRole role) {
  switch (role) {
    case TextRole::seam: return "#0b57a8";
    case TextRole::panel: return "#444";
    default: return "#000";
  }
}

const char* dxf_layer(LineStyle style) {
  switch (style) {
    case LineStyle::cut: return "CUT";
    case LineStyle::mountain: return "MOUNTAIN";
    case LineStyle::valley: return "VALLEY";
    case LineStyle::flat: return "FLAT";
    case LineStyle::tab_fold: return "TAB_FOLD";
    case LineStyle::frame: return "FRAME";
  }
  return "0";
}

}  // namespace

/// Font size giving capital height h (DejaVu Sans and Helvetica: capitals 0.72 em).
double font_size_for_capitals(double h) { return h / 0.72; }

std::string sheet_page_svg(const CutSheets& s, std::size_t k) {
  const SheetPage& page = s.pages.at(k);
  const double H = s.page.y();
  auto X = [](const Vec2& p) { return n(p.x()); };
  auto Y = [H](const Vec2& p) { return n(H - p.y()); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << n(s.page.x()) << "mm\" height=\"" << n(H)
      << "mm\" viewBox=\"0 0 " << n(s.page.x()) << ' ' << n(H) << "\">\n<title>" << escape(s.name) << ": cut sheet "
      << k + 1 << " of " << s.pages.size() << " (" << to_string(s.mode) << "), mm, " << format_number(s.scale)
      << " mm per model unit</title>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (const SheetFill& f : page.fills) {
    svg << "<polygon fill=\"" << svg_fill(f.style) << '"';
    if (f.panel) svg << " class=\"not-cuttable\" data-panel=\"" << *f.panel << '"';
    svg << " points=\"";
    for (const Vec2& c : f.outline) svg << X(c) << ',' << Y(c) << ' ';
    svg << "\"/>\n";
  }
  svg << "<g fill=\"none\" stroke-linecap=\"round\">\n";
  for (const SheetLine& l : page.lines) {
    svg << "<line x1=\"" << X(l.a) << "\" y1=\"" << Y(l.a) << "\" x2=\"" << X(l.b) << "\" y2=\"" << Y(l.b) << "\" "
        << svg_style(l.style) << "/>\n";
  }
  svg << "</g>\n<g font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  for (const SheetText& t : page.texts) {
    const double degrees = std::atan2(t.box.axis.y(), t.box.axis.x()) * 180.0 / M_PI;
    svg << "<text x=\"" << X(t.box.origin) << "\" y=\"" << Y(t.box.origin) << "\" font-size=\""
        << n(font_size_for_capitals(t.box.height)) << "\" textLength=\"" << n(t.box.width)
        << "\" lengthAdjust=\"spacingAndGlyphs\" fill=\"" << text_colour(t.role) << '"'
        << (t.role == TextRole::title ? " font-weight=\"bold\"" : "");
    if (std::abs(degrees) > 1e-9) svg << " transform=\"rotate(" << n(-degrees) << ' ' << X(t.box.origin) << ' ' << Y(t.box.origin) << ")\"";
    svg << '>' << escape(t.text) << "</text>\n";
  }
  svg << "</g>\n</svg>\n";
  return svg.str();
}

std::string cut_sheets_dxf(const CutSheets& s) {
  std::ostringstream dxf;
  dxf << "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n";
  dxf << "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n7\n";
  for (const auto& [layer, colour] : {std::pair{"CUT", 7}, {"MOUNTAIN", 1}, {"VALLEY", 5}, {"FLAT", 8},
                                      {"TAB_FOLD", 8}, {"FRAME", 9}, {"LABELS", 3}}) {
    dxf << "0\nLAYER\n2\n" << layer << "\n70\n0\n62\n" << colour << "\n6\nCONTINUOUS\n";
  }
  dxf << "0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
  for (std::size_t k = 0; k < s.pages.size(); ++k) {
    const Vec2 shift(static_cast<double>(k) * (s.page.x() + 10.0), 0.0);
    auto line = [&](const char* layer, Vec2 a, Vec2 b) {
      a += shift, b += shift;
      dxf << "0\nLINE\n8\n" << layer << "\n10\n" << n(a.x()) << "\n20\n" << n(a.y()) << "\n30\n0\n11\n" << n(b.x())
          << "\n21\n" << n(b.y()) << "\n31\n0\n";
    };
    const Vec2 c0(0, 0), c1(s.page.x(), 0), c2 = s.page, c3(0, s.page.y());
    line("FRAME", c0, c1), line("FRAME", c1, c2), line("FRAME", c2, c3), line("FRAME", c3, c0);
    for (const SheetLine& l : s.pages[k].lines) line(dxf_layer(l.style), l.a, l.b);
    for (const SheetText& t : s.pages[k].texts) {
      const Vec2 at = t.box.origin + shift;
      dxf << "0\nTEXT\n8\nLABELS\n10\n" << n(at.x()) << "\n20\n" << n(at.y()) << "\n30\n0\n40\n" << n(t.box.height)
          << "\n1\n" << t.text << "\n50\n" << n(std::atan2(t.box.axis.y(), t.box.axis.x()) * 180.0 / M_PI) << "\n";
    }
  }
  dxf << "0\nENDSEC\n0\nEOF\n";
  return dxf.str();
}

}  // namespace phedra
