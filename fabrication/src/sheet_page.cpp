// A page's renderers and the legend and scale-bar builders (sheet_page.h).

#include "phedra/sheet_page.h"

#include "phedra/cut_loops.h"
#include "phedra/number_format.h"
#include "phedra/xml_text.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string_view>

namespace phedra {
namespace {

const char* style_class(LineStyle style) {
  switch (style) {
    case LineStyle::cut: return "cut";
    case LineStyle::mountain: return "mountain";
    case LineStyle::valley: return "valley";
    case LineStyle::flat: return "flat";
    case LineStyle::tab_fold: return "tab-fold";
    case LineStyle::frame: return "frame";
    case LineStyle::axis: return "axis";
    case LineStyle::hinge: return "hinge";
    case LineStyle::leader: return "leader";
  }
  return "";
}

const char* svg_style(LineStyle style, bool key) {
  switch (style) {
    // Pure red for the cuts a laser makes; the key's sample of them a red of another value.
    case LineStyle::cut: return key ? "stroke=\"#d00000\" stroke-width=\"0.25\"" : "stroke=\"#ff0000\" stroke-width=\"0.25\"";
    case LineStyle::mountain: return "stroke=\"#c62828\" stroke-width=\"0.3\" stroke-dasharray=\"3 1 0.6 1\"";
    case LineStyle::valley: return "stroke=\"#1e5bb8\" stroke-width=\"0.3\" stroke-dasharray=\"2.5 1.2\"";
    case LineStyle::flat: return "stroke=\"#2e7d32\" stroke-width=\"0.3\" stroke-dasharray=\"0.1 0.9\"";
    case LineStyle::tab_fold: return "stroke=\"#999\" stroke-width=\"0.15\"";
    case LineStyle::frame: return "stroke=\"#ccc\" stroke-width=\"0.2\"";
    case LineStyle::axis: return "stroke=\"#999\" stroke-width=\"0.2\" stroke-dasharray=\"4 1.5\"";
    case LineStyle::hinge: return "stroke=\"#8e24aa\" stroke-width=\"0.2\" stroke-dasharray=\"1 0.8\"";
    case LineStyle::leader: return "stroke=\"#555\" stroke-width=\"0.12\"";
  }
  return "";
}

const char* svg_fill(FillStyle style) {
  switch (style) {
    case FillStyle::tab:
    case FillStyle::swatch_tab: return "#e4e4e4";
    case FillStyle::not_cuttable:
    case FillStyle::swatch_not_cuttable: return "#f4a6a6";
    case FillStyle::marker: return "#888";
    case FillStyle::view_joined: return "#c8c8c8";
    case FillStyle::view_added: return "#f29b38";
    case FillStyle::view_later: return "#fff";
  }
  return "none";
}

bool outlined(FillStyle style) {
  return style == FillStyle::view_joined || style == FillStyle::view_added || style == FillStyle::view_later;
}

const char* text_colour(TextRole role) {
  switch (role) {
    case TextRole::seam: return "#0b57a8";
    case TextRole::panel: return "#444";
    case TextRole::warning: return "#b3261e";
    default: return "#000";
  }
}

/// 1, 2 or 5 times a power of ten, at most x.
double round_down_125(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * p <= x) return m * p;
  }
  return p;
}

}  // namespace

const char* layer_name(const SheetLine& line) {
  if (line.key) return "KEY";
  switch (line.style) {
    case LineStyle::cut: return "CUT";
    case LineStyle::mountain: return "MOUNTAIN";
    case LineStyle::valley: return "VALLEY";
    case LineStyle::flat: return "FLAT";
    case LineStyle::tab_fold: return "TAB_FOLD";
    case LineStyle::frame: return "FRAME";
    case LineStyle::axis: return "AXIS";
    case LineStyle::hinge: return "HINGE";
    case LineStyle::leader: return "LABELS";  // marked with the labels, never cut
  }
  return "0";
}

std::string sheet_number(double x) {
  // Sheets are in mm: a ten-thousandth of a millimetre is finer than any cutter (and of a degree, any angle).
  const double r = std::round(x * 1e4) / 1e4;
  return format_number(r == 0.0 ? 0.0 : r);
}

double font_size_for_capitals(double h) { return h / 0.72; }

namespace {

// DejaVu Sans's advance widths (font units, 2048 an em) of the printable ASCII
// characters, ' ' to '~', regular and bold: read from the font files
// (fonts-dejavu-core, hmtx table). Pages name DejaVu Sans first, and the PDF
// and PNG renderer draws with it.
constexpr std::array<unsigned short, 95> dejavu_regular{
    651,  821,  942,  1716, 1303, 1946, 1597, 563,  799,  799,  1024, 1716, 651,  739,  651,  690,  1303, 1303, 1303,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 690,  690,  1716, 1716, 1716, 1087, 2048, 1401, 1405, 1430, 1577, 1294,
    1178, 1587, 1540, 604,  604,  1343, 1141, 1767, 1532, 1612, 1235, 1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403,
    1251, 1403, 799,  690,  799,  1716, 1024, 1024, 1255, 1300, 1126, 1300, 1260, 721,  1300, 1298, 569,  569,  1186,
    569,  1995, 1298, 1253, 1300, 1300, 842,  1067, 803,  1298, 1212, 1675, 1212, 1212, 1075, 1303, 690,  1303, 1716};
constexpr std::array<unsigned short, 95> dejavu_bold{
    713,  934,  1067, 1716, 1425, 2052, 1786, 627,  936,  936,  1071, 1716, 778,  850,  778,  748,  1425, 1425, 1425,
    1425, 1425, 1425, 1425, 1425, 1425, 1425, 819,  819,  1716, 1716, 1716, 1188, 2048, 1585, 1561, 1503, 1700, 1399,
    1399, 1681, 1714, 762,  762,  1587, 1305, 2038, 1714, 1741, 1501, 1741, 1577, 1475, 1397, 1663, 1585, 2259, 1579,
    1483, 1485, 936,  748,  936,  1716, 1024, 1024, 1382, 1466, 1214, 1466, 1389, 891,  1466, 1458, 702,  702,  1362,
    702,  2134, 1458, 1407, 1466, 1466, 1010, 1219, 979,  1458, 1335, 1892, 1321, 1335, 1192, 1458, 748,  1458, 1716};

}  // namespace

double text_width(const std::string& text, double height, bool bold) {
  const auto& widths = bold ? dejavu_bold : dejavu_regular;
  double units = 0.0;
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      units += widths[u - 0x20];
    } else if (u >= 0xc0) {  // a character beyond ASCII (UTF-8's first byte; the rest add nothing): a digit's width
      units += widths['0' - 0x20];
    }
  }
  // Font units to the em, the em to capital heights (font_size_for_capitals).
  return units / 2048.0 * font_size_for_capitals(height);
}

void add_text(SheetPage& page, const std::string& s, Vec2 at, double h, TextRole role) {
  const bool bold = role == TextRole::title || role == TextRole::warning;
  page.texts.push_back(SheetText{s, Box2{at, Vec2::UnitX(), text_width(s, h, bold), h}, role});
}

void Legend::room(double width) {
  if (x_ > left_ && x_ + width > right_) x_ = left_, row_ -= 2.7 * h_;
}

void Legend::line(LineStyle style, const std::string& what) {
  room(12.0 + text_width(what, h_));
  page_.lines.push_back(SheetLine{Vec2(x_, row_ + 0.36 * h_), Vec2(x_ + 10.0, row_ + 0.36 * h_), style, true});
  add_text(page_, what, Vec2(x_ + 12.0, row_), h_);
  x_ += 12.0 + text_width(what, h_) + 6.0;
}

void Legend::fill(FillStyle style, const std::string& what) {
  room(12.0 + text_width(what, h_));
  const double y0 = row_ - 0.2 * h_, y1 = row_ + 1.2 * h_;
  Polygon2 shape = style == FillStyle::marker
                       ? Polygon2{Vec2(x_ + 4.4, row_ + 0.1 * h_), Vec2(x_ + 5.6, row_ + 0.1 * h_), Vec2(x_ + 5.6, row_ + 0.1 * h_ + 1.2),
                                  Vec2(x_ + 4.4, row_ + 0.1 * h_ + 1.2)}
                       : Polygon2{Vec2(x_, y0), Vec2(x_ + 10.0, y0), Vec2(x_ + 8.0, y1), Vec2(x_ + 2.0, y1)};
  page_.fills.push_back(SheetFill{std::move(shape), style, std::nullopt});
  add_text(page_, what, Vec2(x_ + 12.0, row_), h_);
  x_ += 12.0 + text_width(what, h_) + 6.0;
}

void Legend::sample(const std::string& label, TextRole role, const std::string& what) {
  room(text_width(label, h_) + 2.0 + text_width(what, h_));
  add_text(page_, label, Vec2(x_, row_), h_, role);
  x_ += text_width(label, h_) + 2.0;
  add_text(page_, what, Vec2(x_, row_), h_);
  x_ += text_width(what, h_) + 6.0;
}

void Legend::note(const std::string& what) {
  room(text_width(what, h_));
  add_text(page_, what, Vec2(x_, row_), h_, TextRole::note);
  x_ += text_width(what, h_) + 6.0;
}

void Legend::warning(const std::string& what) {
  const double width = text_width(what, h_, true);
  room(width);
  page_.texts.push_back(SheetText{what, Box2{Vec2(x_, row_), Vec2::UnitX(), width, h_}, TextRole::warning});
  x_ += width + 6.0;
}

void add_scale_bar(SheetPage& page, Vec2 at, double scale, double longest) {
  const double bar = round_down_125(longest);
  page.lines.push_back(SheetLine{at + Vec2(0, 1.0), at + Vec2(bar, 1.0), LineStyle::cut, true});
  page.lines.push_back(SheetLine{at, at + Vec2(0, 2.0), LineStyle::cut, true});
  page.lines.push_back(SheetLine{at + Vec2(bar, 0), at + Vec2(bar, 2.0), LineStyle::cut, true});
  add_text(page, format_significant(bar) + " mm = " + format_significant(bar / scale) + " model units", at + Vec2(bar + 3.0, 0.0), 2.2, TextRole::note);
}

std::string page_svg(const SheetPage& page, Vec2 size, const std::string& title) {
  const double H = size.y();
  auto X = [](const Vec2& p) { return sheet_number(p.x()); };
  auto Y = [H](const Vec2& p) { return sheet_number(H - p.y()); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" width=\"" << sheet_number(size.x()) << "mm\" height=\"" << sheet_number(H)
      << "mm\" viewBox=\"0 0 " << sheet_number(size.x()) << ' ' << sheet_number(H) << "\">\n<title>" << xml_escape(title)
      << "</title>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (const SheetFill& f : page.fills) {
    svg << "<polygon fill=\"" << svg_fill(f.style) << '"';
    if (f.panel) svg << " class=\"not-cuttable\" data-panel=\"" << *f.panel << '"';
    if (outlined(f.style)) svg << " stroke=\"" << (f.style == FillStyle::view_later ? "#bbb" : "#444") << "\" stroke-width=\"0.08\" stroke-linejoin=\"round\"";
    svg << " points=\"";
    for (const Vec2& c : f.outline) svg << X(c) << ',' << Y(c) << ' ';
    svg << "\"/>\n";
  }
  auto layer = [&](const char* name) {
    svg << "<g id=\"" << name << "\" inkscape:groupmode=\"layer\" inkscape:label=\"" << name
        << "\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
  };
  // The cuts as a cutter follows them: closed outlines, inner ones first (cut_loops.h).
  const CutLoops cuts = cut_loops(page.lines);
  if (!cuts.closed.empty() || !cuts.open.empty()) {
    layer("CUT");
    auto points = [&](const std::vector<Vec2>& chain) {
      std::string out;
      for (const Vec2& c : chain) out += X(c) + ',' + Y(c) + ' ';
      return out;
    };
    for (const Polygon2& loop : cuts.closed) svg << "<polygon class=\"cut\" points=\"" << points(loop) << "\" " << svg_style(LineStyle::cut, false) << "/>\n";
    for (const std::vector<Vec2>& chain : cuts.open) svg << "<polyline class=\"cut\" points=\"" << points(chain) << "\" " << svg_style(LineStyle::cut, false) << "/>\n";
    svg << "</g>\n";
  }
  auto line = [&](const SheetLine& l) {
    svg << "<line class=\"" << style_class(l.style) << "\" x1=\"" << X(l.a) << "\" y1=\"" << Y(l.a) << "\" x2=\"" << X(l.b) << "\" y2=\"" << Y(l.b) << "\" "
        << svg_style(l.style, l.key) << "/>\n";
  };
  for (const char* name : {"HINGE", "MOUNTAIN", "VALLEY", "FLAT", "TAB_FOLD", "AXIS", "FRAME", "KEY"}) {
    bool opened = false;
    for (const SheetLine& l : page.lines) {
      if ((l.style == LineStyle::cut && !l.key) || std::string_view(layer_name(l)) != name) continue;
      if (!opened) layer(name), opened = true;
      line(l);
    }
    if (opened) svg << "</g>\n";
  }
  // The labels and their leaders.
  layer("LABELS");
  for (const SheetLine& l : page.lines) {
    if (l.style == LineStyle::leader && !l.key) line(l);
  }
  svg << "<g font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" stroke=\"none\">\n";
  for (const SheetText& t : page.texts) {
    const double degrees = std::atan2(t.box.axis.y(), t.box.axis.x()) * 180.0 / M_PI;
    svg << "<text x=\"" << X(t.box.origin) << "\" y=\"" << Y(t.box.origin) << "\" font-size=\""
        << sheet_number(font_size_for_capitals(t.box.height)) << "\" textLength=\"" << sheet_number(t.box.width)
        << "\" lengthAdjust=\"spacingAndGlyphs\" fill=\"" << text_colour(t.role) << '"'
        << (t.role == TextRole::title || t.role == TextRole::warning ? " font-weight=\"bold\"" : "");
    if (std::abs(degrees) > 1e-9) svg << " transform=\"rotate(" << sheet_number(-degrees) << ' ' << X(t.box.origin) << ' ' << Y(t.box.origin) << ")\"";
    svg << '>' << xml_escape(t.text) << "</text>\n";
  }
  svg << "</g>\n</g>\n</svg>\n";
  return svg.str();
}

}  // namespace phedra
