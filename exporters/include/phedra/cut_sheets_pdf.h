#pragma once
// Cut sheets drawn with cairo (Debian's libcairo2): every page of a PDF, or
// one page as a PNG picture.

#include "phedra/cut_sheets.h"

#include <string>

namespace phedra {

/// A PDF with one page per sheet page, in their size (mm).
std::string cut_sheets_pdf(const CutSheets& sheets);

/// Page `page` as a PNG at `dpi` dots per inch.
std::string sheet_page_png(const CutSheets& sheets, std::size_t page, double dpi = 150.0);

}  // namespace phedra
