// Cut sheets as DXF R2000 through dxflib (Debian's libdxflib-dev): every page
// side by side in millimetres. A laser's or a CAM tool's reading: each cut
// outline one closed LWPOLYLINE on CUT, inner ones before outer (cut_loops.h);
// hinge, fold and tab lines on their layers; the frame, the labels and the key
// (the legend's samples, the scale bar) on theirs, never on CUT.

#include "phedra/cut_loops.h"
#include "phedra/cut_sheets.h"

#include <dxflib/dl_dxf.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace phedra {
namespace {

/// Layers and their colours (AutoCAD colour index): CUT white/black, the folds red and blue.
constexpr std::pair<const char*, int> layers[] = {{"0", 7},        {"CUT", 7},    {"HINGE", 6}, {"MOUNTAIN", 1},
                                                  {"VALLEY", 5},   {"FLAT", 8},   {"TAB_FOLD", 8}, {"AXIS", 8},
                                                  {"FRAME", 9},    {"LABELS", 3}, {"KEY", 4}};
constexpr int by_layer = 256;

/// dxflib writes to a file only: a private temporary file, read back and removed.
class ScratchFile {
 public:
  ScratchFile() {
    static std::atomic<unsigned> count{0};
    path_ = std::filesystem::temp_directory_path() /
            ("phedra-dxf-" + std::to_string(::getpid()) + "-" + std::to_string(count++) + ".dxf");
  }
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

std::string cut_sheets_dxf(const CutSheets& s) {
  const ScratchFile file;
  DL_Dxf dxf;
  {
    std::unique_ptr<DL_WriterA> w(dxf.out(file.path().c_str(), DL_Codes::AC1015));
    if (!w) throw std::runtime_error("DXF: cannot write the scratch file " + file.path().string());
    DL_WriterA& dw = *w;
    dxf.writeHeader(dw);
    dw.dxfString(9, "$INSUNITS");
    dw.dxfInt(70, 4);  // millimetres
    dw.sectionEnd();
    dw.sectionTables();
    dxf.writeVPort(dw);
    dw.tableLinetypes(3);
    dxf.writeLinetype(dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
    dxf.writeLinetype(dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
    dxf.writeLinetype(dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
    dw.tableEnd();
    dw.tableLayers(static_cast<int>(std::size(layers)));
    for (const auto& [name, colour] : layers) {
      dxf.writeLayer(dw, DL_LayerData(name, 0), DL_Attributes("", colour, 0, "CONTINUOUS", 1.0));
    }
    dw.tableEnd();
    dw.tableStyle(1);
    dxf.writeStyle(dw, DL_StyleData("standard", 0, 0.0, 1.0, 0.0, 0, 2.5, "DejaVuSans.ttf", ""));
    dw.tableEnd();
    dxf.writeView(dw);
    dxf.writeUcs(dw);
    dw.tableAppid(1);
    dxf.writeAppid(dw, "ACAD");
    dw.tableEnd();
    dxf.writeDimStyle(dw, 1, 1, 1, 1, 1);
    dxf.writeBlockRecord(dw);
    dw.tableEnd();
    dw.sectionEnd();
    dw.sectionBlocks();
    dxf.writeBlock(dw, DL_BlockData("*Model_Space", 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(dw, "*Model_Space");
    dxf.writeBlock(dw, DL_BlockData("*Paper_Space", 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(dw, "*Paper_Space");
    dxf.writeBlock(dw, DL_BlockData("*Paper_Space0", 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(dw, "*Paper_Space0");
    dw.sectionEnd();

    dw.sectionEntities();
    auto on = [](const char* layer) { return DL_Attributes(layer, by_layer, 0, "BYLAYER", 1.0); };
    // A key's sample line: on KEY, in the colour of the layer it shows (a mountain fold's red, ...).
    auto key_sample = [](const SheetLine& l) {
      SheetLine shown = l;
      shown.key = false;
      int colour = by_layer;
      for (const auto& [name, c] : layers) {
        if (std::string_view(name) == layer_name(shown)) colour = c;
      }
      return DL_Attributes("KEY", colour, 0, "BYLAYER", 1.0);
    };
    auto polyline = [&](const std::vector<Vec2>& points, bool closed, const char* layer, const Vec2& shift) {
      dxf.writePolyline(dw, DL_PolylineData(static_cast<int>(points.size()), 0, 0, closed ? 1 : 0), on(layer));
      for (const Vec2& p : points) dxf.writeVertex(dw, DL_VertexData(p.x() + shift.x(), p.y() + shift.y(), 0.0, 0.0));
      dxf.writePolylineEnd(dw);
    };
    for (std::size_t k = 0; k < s.pages.size(); ++k) {
      const Vec2 shift(static_cast<double>(k) * (s.page.x() + 10.0), 0.0);
      polyline({Vec2(0, 0), Vec2(s.page.x(), 0), s.page, Vec2(0, s.page.y())}, true, "FRAME", shift);
      const CutLoops cuts = cut_loops(s.pages[k].lines);
      for (const Polygon2& loop : cuts.closed) polyline(loop, true, "CUT", shift);
      for (const std::vector<Vec2>& chain : cuts.open) polyline(chain, false, "CUT", shift);
      for (const SheetLine& l : s.pages[k].lines) {
        if (l.style == LineStyle::cut && !l.key) continue;  // in the loops above
        dxf.writeLine(dw, DL_LineData(l.a.x() + shift.x(), l.a.y() + shift.y(), 0.0, l.b.x() + shift.x(), l.b.y() + shift.y(), 0.0),
                      l.key ? key_sample(l) : on(layer_name(l)));
      }
      for (const SheetText& t : s.pages[k].texts) {
        const Vec2 at = t.box.origin + shift;
        dxf.writeText(dw, DL_TextData(at.x(), at.y(), 0.0, at.x(), at.y(), 0.0, t.box.height, 1.0, 0, 0, 0, t.text, "standard",
                                      std::atan2(t.box.axis.y(), t.box.axis.x())),
                      on("LABELS"));
      }
    }
    dw.sectionEnd();
    dxf.writeObjects(dw);
    dxf.writeObjectsEnd(dw);
    dw.dxfEOF();
    dw.close();
  }
  std::ifstream in(file.path(), std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in.good() && !in.eof()) throw std::runtime_error("DXF: cannot read the scratch file back");
  return bytes.str();
}

}  // namespace phedra
