#include "phedra/sheet_page.h"

#include "phedra/errors.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>
#include <memory>

namespace phedra {
namespace {

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_line(cairo_t* cr, LineStyle style) {
  auto dash = [cr](std::initializer_list<double> d) {
    const std::vector<double> v(d);
    cairo_set_dash(cr, v.data(), static_cast<int>(v.size()), 0.0);
  };
  switch (style) {
    case LineStyle::cut: cairo_set_source_rgb(cr, 0, 0, 0), cairo_set_line_width(cr, 0.25), dash({}); break;
    case LineStyle::mountain: cairo_set_source_rgb(cr, 0.78, 0.16, 0.16), cairo_set_line_width(cr, 0.3), dash({3, 1, 0.6, 1}); break;
    case LineStyle::valley: cairo_set_source_rgb(cr, 0.12, 0.36, 0.72), cairo_set_line_width(cr, 0.3), dash({2.5, 1.2}); break;
    case LineStyle::flat: cairo_set_source_rgb(cr, 0.18, 0.49, 0.2), cairo_set_line_width(cr, 0.3), dash({0.1, 0.9}); break;
    case LineStyle::tab_fold: cairo_set_source_rgb(cr, 0.6, 0.6, 0.6), cairo_set_line_width(cr, 0.15), dash({}); break;
    case LineStyle::frame: cairo_set_source_rgb(cr, 0.8, 0.8, 0.8), cairo_set_line_width(cr, 0.2), dash({}); break;
    case LineStyle::axis: cairo_set_source_rgb(cr, 0.6, 0.6, 0.6), cairo_set_line_width(cr, 0.2), dash({4, 1.5}); break;
    case LineStyle::hinge: cairo_set_source_rgb(cr, 0.56, 0.14, 0.67), cairo_set_line_width(cr, 0.2), dash({1, 0.8}); break;
    case LineStyle::leader: cairo_set_source_rgb(cr, 0.33, 0.33, 0.33), cairo_set_line_width(cr, 0.12), dash({}); break;
  }
}

/// Draws a page in mm (y up on the sheet, down in cairo).
void draw(cairo_t* cr, const SheetPage& page, double H) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  for (const SheetFill& f : page.fills) {
    const bool tab = f.style == FillStyle::tab || f.style == FillStyle::swatch_tab;
    const bool view = f.style == FillStyle::view_joined || f.style == FillStyle::view_added || f.style == FillStyle::view_later;
    if (f.style == FillStyle::marker) {
      cairo_set_source_rgb(cr, 0.53, 0.53, 0.53);
    } else if (f.style == FillStyle::view_joined) {
      cairo_set_source_rgb(cr, 0.784, 0.784, 0.784);
    } else if (f.style == FillStyle::view_added) {
      cairo_set_source_rgb(cr, 0.949, 0.608, 0.22);
    } else if (f.style == FillStyle::view_later) {
      cairo_set_source_rgb(cr, 1, 1, 1);
    } else {
      tab ? cairo_set_source_rgb(cr, 0.894, 0.894, 0.894) : cairo_set_source_rgb(cr, 0.957, 0.651, 0.651);
    }
    for (std::size_t i = 0; i < f.outline.size(); ++i) {
      (i ? cairo_line_to : cairo_move_to)(cr, f.outline[i].x(), H - f.outline[i].y());
    }
    cairo_close_path(cr);
    if (!view) {
      cairo_fill(cr);
      continue;
    }
    cairo_fill_preserve(cr);  // outlined: the faces of a 3D view, drawn far to near
    const double grey = f.style == FillStyle::view_later ? 0.73 : 0.27;
    cairo_set_source_rgb(cr, grey, grey, grey);
    cairo_set_line_width(cr, 0.08);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    cairo_stroke(cr);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const SheetLine& l : page.lines) {
    set_line(cr, l.style);
    cairo_move_to(cr, l.a.x(), H - l.a.y());
    cairo_line_to(cr, l.b.x(), H - l.b.y());
    cairo_stroke(cr);
  }
  for (const SheetText& t : page.texts) {
    const bool bold = t.role == TextRole::title || t.role == TextRole::warning;
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, font_size_for_capitals(t.box.height));
    cairo_text_extents_t extents;
    cairo_text_extents(cr, t.text.c_str(), &extents);
    if (t.role == TextRole::seam) {
      cairo_set_source_rgb(cr, 0.043, 0.341, 0.659);
    } else if (t.role == TextRole::panel) {
      cairo_set_source_rgb(cr, 0.27, 0.27, 0.27);
    } else if (t.role == TextRole::warning) {
      cairo_set_source_rgb(cr, 0.702, 0.149, 0.118);
    } else {
      cairo_set_source_rgb(cr, 0, 0, 0);
    }
    cairo_save(cr);
    cairo_translate(cr, t.box.origin.x(), H - t.box.origin.y());
    cairo_rotate(cr, -std::atan2(t.box.axis.y(), t.box.axis.x()));
    // Stretch the text to exactly its box (the same box the SVG's textLength fills).
    if (extents.x_advance > 0.0) cairo_scale(cr, t.box.width / extents.x_advance, 1.0);
    cairo_move_to(cr, 0, 0);
    cairo_show_text(cr, t.text.c_str());
    cairo_restore(cr);
  }
}

void check(cairo_status_t status, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(ExitCode::internal, std::string("cairo could not draw the ") + what + ": " + cairo_status_to_string(status));
  }
}

}  // namespace

std::string pages_pdf(const std::vector<SheetPage>& pages, Vec2 size, const std::string& title) {
  std::string out;
  const double points = 72.0 / 25.4;
  cairo_surface_t* surface = cairo_pdf_surface_create_for_stream(append, &out, size.x() * points, size.y() * points);
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, title.c_str());
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "phedra");
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, points, points);
  for (const SheetPage& page : pages) {
    draw(cr, page, size.y());
    cairo_show_page(cr);
  }
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t surface_status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  check(status, "PDF");
  check(surface_status, "PDF");
  return out;
}

std::string page_png(const SheetPage& page, Vec2 size, double dpi) {
  const double pixels = dpi / 25.4;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(std::ceil(size.x() * pixels)),
                                                        static_cast<int>(std::ceil(size.y() * pixels)));
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, pixels, pixels);
  draw(cr, page, size.y());
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  std::string out;
  const cairo_status_t written = cairo_surface_write_to_png_stream(surface, append, &out);
  cairo_surface_destroy(surface);
  check(status, "PNG");
  check(written, "PNG");
  return out;
}

}  // namespace phedra
