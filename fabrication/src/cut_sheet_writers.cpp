// Cut sheets as SVG (one file per page, in mm), PDF (every page) and DXF (every page side by side).

#include "phedra/cut_sheets.h"

#include "phedra/number_format.h"

#include <cmath>
#include <sstream>

namespace phedra {
namespace {

const char* dxf_layer(LineStyle style) {
  switch (style) {
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


std::string title(const CutSheets& s, std::size_t k) {
  return s.name + ": cut sheet " + std::to_string(k + 1) + " of " + std::to_string(s.pages.size()) + " (" +
         to_string(s.mode) + "), mm, " + format_number(s.scale) + " mm per model unit";
}

}  // namespace

std::string sheet_page_svg(const CutSheets& s, std::size_t k) { return page_svg(s.pages.at(k), s.page, title(s, k)); }

std::string cut_sheets_pdf(const CutSheets& s) { return pages_pdf(s.pages, s.page, s.name + " - cut sheets"); }

std::string cut_sheets_dxf(const CutSheets& s) {
  std::ostringstream dxf;
  dxf << "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n";
  dxf << "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n8\n";
  for (const auto& [layer, colour] : {std::pair{"CUT", 7}, {"MOUNTAIN", 1}, {"VALLEY", 5}, {"FLAT", 8},
                                      {"TAB_FOLD", 8}, {"FRAME", 9}, {"LABELS", 3}, {"HINGE", 6}}) {
    dxf << "0\nLAYER\n2\n" << layer << "\n70\n0\n62\n" << colour << "\n6\nCONTINUOUS\n";
  }
  dxf << "0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
  for (std::size_t k = 0; k < s.pages.size(); ++k) {
    const Vec2 shift(static_cast<double>(k) * (s.page.x() + 10.0), 0.0);
    auto line = [&](const char* layer, Vec2 a, Vec2 b) {
      a += shift, b += shift;
      dxf << "0\nLINE\n8\n" << layer << "\n10\n" << sheet_number(a.x()) << "\n20\n" << sheet_number(a.y()) << "\n30\n0\n11\n" << sheet_number(b.x())
          << "\n21\n" << sheet_number(b.y()) << "\n31\n0\n";
    };
    const Vec2 c0(0, 0), c1(s.page.x(), 0), c2 = s.page, c3(0, s.page.y());
    line("FRAME", c0, c1), line("FRAME", c1, c2), line("FRAME", c2, c3), line("FRAME", c3, c0);
    for (const SheetLine& l : s.pages[k].lines) line(dxf_layer(l.style), l.a, l.b);
    for (const SheetText& t : s.pages[k].texts) {
      const Vec2 at = t.box.origin + shift;
      dxf << "0\nTEXT\n8\nLABELS\n10\n" << sheet_number(at.x()) << "\n20\n" << sheet_number(at.y()) << "\n30\n0\n40\n" << sheet_number(t.box.height)
          << "\n1\n" << t.text << "\n50\n" << sheet_number(std::atan2(t.box.axis.y(), t.box.axis.x()) * 180.0 / M_PI) << "\n";
    }
  }
  dxf << "0\nENDSEC\n0\nEOF\n";
  return dxf.str();
}

}  // namespace phedra
