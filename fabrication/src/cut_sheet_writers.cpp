// Cut sheets as SVG (one file per page, in mm) and PDF (every page); the DXF: cut_sheet_dxf.cpp.

#include "phedra/cut_sheets.h"

#include "phedra/number_format.h"

#include <sstream>

namespace phedra {
namespace {

/// Names what the sheet holds as drawn: plates of a thickness, or card pieces of a mode.
std::string title(const CutSheets& s, std::size_t k) {
  const std::string what = s.thick ? "plates " + format_significant(s.thickness_mm) + " mm thick" : to_string(s.mode);
  return s.name + ": cut sheet " + std::to_string(k + 1) + " of " + std::to_string(s.pages.size()) + " (" + what +
         "), mm, " + format_number(s.scale) + " mm per model unit";
}

}  // namespace

std::string sheet_page_svg(const CutSheets& s, std::size_t k) { return page_svg(s.pages.at(k), s.page, title(s, k)); }

std::string cut_sheets_pdf(const CutSheets& s) { return pages_pdf(s.pages, s.page, s.name + " - cut sheets"); }

}  // namespace phedra
