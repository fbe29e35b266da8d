// libFuzzer harness over the whole pipeline: parse a preset, build the design,
// evaluate it at parameters taken from the input, check it and export it to
// memory (glTF nodes and morph, FOLD, motion JSON, OBJ). phedra::Error is the
// expected answer to a bad input; anything else (a crash, another exception,
// a sanitizer report, a non-finite number in an output) is a finding.

#include "phedra/assembly_check.h"
#include "phedra/crease_pattern.h"
#include "phedra/developed_pattern.h"
#include "phedra/cut_sheets.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/self_intersection.h"
#include "phedra/design.h"
#include "phedra/errors.h"
#include "phedra/fold_export.h"
#include "phedra/gltf_export.h"
#include "phedra/mesh_export.h"
#include "phedra/motion_document.h"
#include "phedra/preset.h"
#include "phedra/buildability.h"
#include "phedra/solid_export.h"
#include "phedra/thick_plates.h"
#include "phedra/design_preset.h"
#include "phedra/developed_preset.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace {

/// Fractions in [0, 1] from the input's last bytes (deterministic per input).
double fraction(const std::uint8_t* data, std::size_t size, std::size_t k) {
  if (size == 0) return 0.5;
  return static_cast<double>(data[(size - 1 - k % size)]) / 255.0;
}

void must(bool ok) {
  if (!ok) std::abort();
}

/// A developed (flat) pattern: the criterion, the folding and the crease pattern.
void developed(const nlohmann::json& document, const std::uint8_t* data, std::size_t size) {
  using namespace phedra;
  const DevelopedPattern pattern(developed_from_json(document));
  if (pattern.strips() * pattern.columns() > 4000) return;
  for (const FlexDirection& f : pattern.flex_directions()) {
    if (!f.folds) continue;
    std::vector<int> fold(pattern.strips(), 1);
    for (std::size_t i = 0; i < fold.size(); ++i) fold[i] = fraction(data, size, i) < 0.5 ? 1 : -1;
    const double t = pattern.t_star() + 0.5 * (f.reach - pattern.t_star());
    const std::optional<Points> x = pattern.folded(t, fold);
    must(x.has_value());
    for (const Vec3& p : *x) must(p.allFinite());
    const CreasePattern c = crease_pattern(pattern, fold, pattern.t_star() + 1e-3 * (f.reach - pattern.t_star()), t);
    crease_svg(c);
    crease_fold(c);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace phedra;
  try {
    const nlohmann::json document = parse_json_text(std::string_view(reinterpret_cast<const char*>(data), size));
    if (document.is_object() && document.contains("developed")) {
      developed(document, data, size);
      return 0;
    }
    const Design design = design_from_json(document);
    const Assembly& a = design.assembly;
    if (a.total_vertex_count() > 4000) return 0;  // big but valid: not what this harness looks for
    const FlexionInterval& f = a.flexion_interval();
    must(f.lower.t < a.t_star() && a.t_star() < f.upper.t);
    for (std::size_t k = 0; k < 3; ++k) {
      const AssemblyConfiguration c = a.evaluate(a.t_at_fraction(fraction(data, size, k)));
      for (const Points& member : c.members) {
        for (const Vec3& p : member) must(p.allFinite());
      }
    }
    // The configuration curve: every pass inside the interval, every branch finite.
    const PHedron& base = a.base();
    const PHedron::ConfigurationCycle cycle = base.configuration_cycle();
    must(!cycle.passes.empty() && (cycle.closed || !cycle.stop.empty()));
    Points on_branch(base.vertex_count());
    for (const PHedron::Pass& pass : cycle.passes) {
      must(base.flexion_interval().contains(pass.from) && base.flexion_interval().contains(pass.to));
      base.evaluate(0.5 * (pass.from + pass.to), pass.flipped, on_branch);
      for (const Vec3& p : on_branch) must(p.allFinite());
    }
    CheckOptions options;
    options.samples = 5;
    const AssemblyCheckReport report = check_assembly(a, options);
    must(!std::isnan(report.planarity.value) || !report.passed());
    GltfOptions gltf;
    gltf.keyframes.maximum = 64;
    gltf_bytes(design, gltf);
    gltf.morph = true;
    gltf.max_morph_targets = 16;
    gltf_bytes(design, gltf);
    const std::vector<double> ts{f.lower.t, a.t_star(), f.upper.t};
    fold_json(design, ts);
    motion_json(motion_document(design), ts);
    mesh_text(design, a.t_star(), ".obj");
    // The analyses: self-intersection, metamaterial figures, fabrication outlines.
    const SelfIntersectionReport intersections = find_self_intersections(design, {.samples_per_side = 8});
    must(intersections.free_lower <= intersections.free_upper);
    metamaterial_metrics(design, {.samples = 5}).to_svg();
    const CutSheets sheets = cut_sheets(design);
    cut_sheets_dxf(sheets);
    sheet_page_svg(sheets, 0);
    // Thick plates (a thickness up to 2 % of the model size from the input): every
    // solid finite and closed with a positive volume, the STL written, plate sheets
    // (one input in sixteen, small designs, one side: the other stages keep their pace).
    if (a.total_vertex_count() > 80 || fraction(data, size, 9) >= 1.0 / 16.0) return 0;
    ThickOptions thick;
    thick.side = fraction(data, size, 8) < 0.5 ? PlateSide::front : PlateSide::back;
    thick.thickness = (0.001 + 0.02 * fraction(data, size, 7)) * a.model_size();
    thick.samples_per_side = 6;
    BuildabilityOptions quick;
    quick.sweep.samples_per_side = 8;
    const ThickReport r = check_thickness(design, assess_buildability(design, nullptr, quick), thick);
    must(r.at_t_star || (r.thick_lower <= r.t_star && r.t_star <= r.thick_upper));
    const ThickPlates plates = thick_plates(design, r);
    const std::vector<Solid> solids = plates.solids(plates.positions(a.t_star()));
    for (const Solid& solid : solids) {
      for (const Vec3& p : solid.vertices) must(p.allFinite());
      must(solid.volume() > 0.0);
    }
    solid_bytes(solids, std::vector<std::string>(solids.size(), "plate"), ".stl");
    CutSheetOptions plate_sheets;
    plate_sheets.plates = PlateCut{3.0, 0.2, thick.side};
    cut_sheets(design, plate_sheets);
  } catch (const Error&) {
    // A clear answer to a bad input (or an internal error refusing a non-finite
    // number, which the writers raise on purpose: treat as a finding).
  }
  return 0;
}
