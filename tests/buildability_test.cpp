// Buildable designs (issue 13): MATH.md section 9's rule against the geometry on
// many random designs, the diagnosis of every invalid panel, the field hints,
// distinct panels of arrays against a brute-force count, and the report.

#include "phedra/buildability.h"
#include "phedra/errors.h"
#include "phedra/field_hints.h"
#include "phedra/files.h"
#include "phedra/panel_nets.h"
#include "phedra/preset.h"
#include "phedra/tube.h"
#include "phedra/tube_array.h"
#include "support/random_input.h"
#include "support/test_files.h"
#include "phedra/design_preset.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

using namespace phedra;

namespace {

using json = nlohmann::json;

/// Smallest |sine| of the axial face's corners and smallest relative edge scale:
/// a panel on the edge of changing shape, where rounding decides (skipped).
bool borderline(const PanelNets& p, const ShapeRule& r) {
  if (p.boundary) {
    const double q = r.scales[p.column == 0 ? 1 : 3];
    return std::abs(q) < 1e-7 || std::abs(q - 1.0) < 1e-7;
  }
  const Vec3 normal = quad_normal(p.axial);
  double largest = 0.0;
  for (double s : r.scales) largest = std::max(largest, std::abs(s));
  for (int k = 0; k < 4; ++k) {
    if (std::abs(r.scales[k]) < 1e-7 * largest) return true;
    const Vec3 in = p.axial[k] - p.axial[(k + 3) % 4], out = p.axial[(k + 1) % 4] - p.axial[k];
    if (std::abs(normal.dot(in.cross(out))) < 1e-7 * in.norm() * out.norm()) return true;
  }
  return false;
}

PanelShape shape_at_t_star(const Design& d, const AssemblyMesh& mesh, const Points& x, std::size_t f) {
  (void)d;
  const Quad& q = mesh.faces[f];
  return panel_shape({x[q[0]], x[q[1]], x[q[2]], x[q[3]]});
}

/// A random design: open P-hedra of every sign pattern (smooth or irregular),
/// parallelogram and anti-parallelogram tubes, and small grids of cells.
std::optional<Design> random_design(std::mt19937_64& rng, int k, int& redrawn) {
  const int kind = k % 6;  // 0-2 open, 3 parallelogram tube, 4 anti-parallelogram tube, 5 grid
  test::RandomInputShape shape;
  shape.strips = kind == 5 ? 2 + k % 5 : 2 + k % 9;
  shape.profile_vertices = kind <= 2 ? 3 + k % 5 : 5;
  shape.smooth = k % 2 == 0;
  std::uniform_real_distribution<double> height(-3.0, 3.0);
  auto tube_heights = [&](TubeType type) {
    TubeHeights z;
    do {
      z = {height(rng), height(rng), height(rng), height(rng)};
      if (type == TubeType::anti_parallelogram) z[3] = z[0] + z[2] - z[1];
    } while (std::abs(z[0] - z[1]) < 0.3 || std::abs(z[1] - z[2]) < 0.3 || std::abs(z[2] - z[3]) < 0.3 ||
             std::abs(z[3] - z[0]) < 0.3 || std::abs(z[0] - z[2]) < 0.3 || std::abs(z[1] - z[3]) < 0.3);
    return z;
  };
  const std::optional<PHedron> p = test::draw_phedron(
      [&] {
        ControlPolylines input = test::random_input(rng, shape);
        if (kind == 3 || kind == 5) set_tube_profile(input, TubeType::parallelogram, tube_heights(TubeType::parallelogram));
        if (kind == 4) set_tube_profile(input, TubeType::anti_parallelogram, tube_heights(TubeType::anti_parallelogram));
        return input;
      },
      redrawn);
  if (!p) return std::nullopt;
  if (kind != 5) return Design{Assembly(*p), false, "random"};
  for (int attempt = 0; attempt < 50; ++attempt) {
    // Families of heights that alternate like a parallelogram cell's (u below, w above).
    std::vector<double> u{height(rng) - 3.0}, w{height(rng) + 3.0};
    for (int c = 0; c < 2; ++c) {
      u.push_back(u.back() + 0.4 + std::abs(height(rng)) / 3.0);
      w.push_back(w.back() - 0.4 - std::abs(height(rng)) / 3.0);
    }
    try {
      TubeGrid grid = make_parallelogram_grid(p->input(), u, w);
      const FlexionInterval& f = grid.assembly.flexion_interval();
      if (!test::well_inside_interval(grid.assembly.t_star(), f.lower.t, f.upper.t, grid.assembly.model_size())) continue;
      return Design{std::move(grid.assembly), false, "grid"};
    } catch (const InvalidInputError&) {
      ++redrawn;
    }
  }
  return std::nullopt;
}

}  // namespace

TEST_CASE("section 9: the axial face and the edge-scale signs predict every panel's shape", "[buildability]") {
  // Over 1200 random designs (open with every sign pattern, both tube kinds,
  // grids): the rule agrees with the geometry on every panel, and the cause of
  // every crossed panel is what the diagnosis says it is.
  std::mt19937_64 rng(20261201);
  int redrawn = 0, designs = 0, faces = 0, skipped = 0, triangles = 0;
  std::map<PanelCause, int> causes;
  std::map<PanelShape, int> shapes;
  int plus_columns = 0;
  for (int k = 0; k < 1200; ++k) {
    const std::optional<Design> d = random_design(rng, k, redrawn);
    if (!d) continue;
    ++designs;
    const Assembly& a = d->assembly;
    const AssemblyMesh mesh = panel_mesh(*d);
    const Points x = mesh.positions(a.evaluate(a.t_star()));
    DiagnosisOptions shapes_only;  // the rule is about shapes: no size bounds here (size_bounds_test.cpp)
    shapes_only.size = {0.0, 0.0, 0.0};
    const std::vector<PanelDiagnosis> invalid = diagnose_panels(*d, mesh, nullptr, shapes_only);
    std::size_t next_invalid = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const PanelNets nets = panel_nets(a, mesh.face_member[f], mesh.face_local[f]);
      const ShapeRule rule = apply_shape_rule(nets);
      const PanelShape shape = shape_at_t_star(*d, mesh, x, f);
      const bool reported = next_invalid < invalid.size() && invalid[next_invalid].panel == f;
      if (reported) ++next_invalid;
      CHECK(reported == !is_valid_panel(shape));  // the diagnosis lists exactly the invalid panels
      if (nets.boundary && rule.scales[nets.column == 0 ? 1 : 3] == 1.0) {
        CHECK(is_valid_panel(shape));  // strip 0's boundary triangles (rows 0 and 1 are the axial net's)
        ++triangles;
        continue;
      }
      if (borderline(nets, rule)) {
        ++skipped;
        continue;
      }
      ++faces;
      ++shapes[shape];
      CAPTURE(k, f, to_string(shape), to_string(rule.predicted), to_string(rule.axial));
      REQUIRE(rule.predicted == shape);
      // The shape margin has the sign of "simple".
      CHECK((shape_margin(nets) > 0.0) == is_valid_panel(shape));
      if (shape != PanelShape::bow_tie) {
        CHECK(rule.cause == PanelCause::none);
        continue;
      }
      ++causes[rule.cause];
      switch (rule.cause) {
        case PanelCause::axial_face_crossed: CHECK(panel_shape(nets.axial) == PanelShape::bow_tie); break;
        case PanelCause::edge_reversed: {
          CHECK(is_valid_panel(panel_shape(nets.axial)));
          REQUIRE(rule.odd_edge >= 0);
          int others_negative = 0;
          for (int e = 0; e < 4; ++e) others_negative += e != rule.odd_edge && rule.scales[e] < 0.0 ? 1 : 0;
          // The odd edge's sign differs from the other three, which agree.
          CHECK((others_negative == 0 || others_negative == 3));
          CHECK((rule.scales[rule.odd_edge] < 0.0) == (others_negative == 0));
          break;
        }
        case PanelCause::boundary_segment_short: {
          REQUIRE(nets.boundary);
          const double q = rule.scales[nets.column == 0 ? 1 : 3];
          CHECK((q > 0.0 && q < 1.0));
          break;
        }
        default: FAIL("a bow-tie without a cause");
      }
      // With sign '+' at S_{j+1} the axial face is crossed exactly when the height
      // of S_{j+1} lies between those of S_j and S_{j+2} (every profile alike).
      if (!nets.boundary && a.signs(mesh.face_member[f])[nets.column] == Sign::plus) {
        const std::vector<double> z = a.apex_heights(mesh.face_member[f]);
        const std::size_t j = nets.column;
        const bool between = (z[j + 1] - z[j]) * (z[j + 1] - z[j + 2]) < 0.0;
        CHECK(between == (rule.cause == PanelCause::axial_face_crossed));
        ++plus_columns;
      }
    }
  }
  INFO("designs " << designs << " (redrawn " << redrawn << "), faces " << faces << ", skipped as borderline " << skipped
                   << ", boundary triangles " << triangles);
  CHECK(designs >= 1000);
  CHECK(faces > 20000);
  CHECK(skipped < faces / 100);
  // Every cause and shape occurs often enough to be tested.
  CHECK(causes[PanelCause::axial_face_crossed] > 100);
  CHECK(causes[PanelCause::edge_reversed] > 100);
  CHECK(causes[PanelCause::boundary_segment_short] > 20);
  CHECK(shapes[PanelShape::non_convex] > 100);
  CHECK(shapes[PanelShape::convex] > 1000);
  CHECK(plus_columns > 50);
}

TEST_CASE("field hints point the way: a small step along a hint turns a corner of the panel towards straight",
          "[buildability]") {
  // For crossed panels of random presets, the hinted field moved by 1 % of the
  // hinted change reduces some corner turn of the panel by about 1 %, and the
  // whole change (a little more) makes the panel simple in about half the cases.
  std::mt19937_64 rng(7);
  int tested = 0, simple_after = 0, redrawn = 0;
  for (int k = 0; k < 120 && tested < 60; ++k) {
    test::RandomInputShape shape;
    shape.strips = 3 + k % 5;
    shape.profile_vertices = 3 + k % 4;
    shape.smooth = true;
    shape.random_placement = false;
    const std::optional<PHedron> p = test::draw_phedron([&] { return test::random_input(rng, shape); }, redrawn);
    REQUIRE(p);
    const json preset = preset_to_json(p->input());
    const Design d = design_from_json(preset);
    const AssemblyMesh mesh = panel_mesh(d);
    const std::vector<PanelDiagnosis> invalid = diagnose_panels(d, mesh, &preset);
    for (const PanelDiagnosis& diag : invalid) {
      if (diag.hints.empty() || diag.shape != PanelShape::bow_tie) continue;
      const FieldHint& hint = diag.hints.front();
      CAPTURE(k, diag.panel, hint.field, hint.value, hint.change);
      const MemberFace face{mesh.face_member[diag.panel], mesh.face_local[diag.panel]};
      const PanelNets before = panel_nets(d.assembly, face.member, face.local);
      const Vec3 normal = quad_normal(before.general);
      const std::array<double, 4> turns = corner_turns(before.general, normal);
      auto moved = [&](double fraction) {
        json changed = preset;
        for (const DesignField& field : design_fields(preset, d.assembly.model_size())) {
          if (field.name == hint.field) changed.at(field.pointer) = hint.value + fraction * hint.change;
        }
        return design_from_json(changed);
      };
      const Design step = moved(0.01);
      const std::array<double, 4> after = corner_turns(panel_nets(step.assembly, face.member, face.local).general, normal);
      double best = 2.0;
      for (int c = 0; c < 4; ++c) best = std::min(best, after[c] / turns[c]);
      CHECK(best == Approx(0.99).margin(0.003));
      try {
        const Design full = moved(1.2);
        const PanelNets n = panel_nets(full.assembly, face.member, face.local);
        simple_after += is_valid_panel(panel_shape(n.general)) ? 1 : 0;
      } catch (const InvalidInputError&) {
      }
      ++tested;
    }
  }
  INFO("hints tested " << tested << ", panel simple after 1.2 x the change: " << simple_after);
  CHECK(tested >= 40);
  CHECK(simple_after * 3 > tested);  // about half of them (the turns are not linear)
}

TEST_CASE("arrays: distinct panels against a brute-force count of coincident member faces", "[buildability]") {
  // Every member face of an array, compared by its corner positions at t*: the
  // panel mesh keeps one panel per distinct place (a shared wall once), and its
  // invalid panels are the distinct invalid places.
  std::mt19937_64 rng(99);
  int redrawn = 0, arrays = 0;
  for (int k = 0; k < 60; ++k) {
    const std::optional<Design> d = random_design(rng, 6 * k + 5, redrawn);
    if (!d) continue;
    ++arrays;
    const Assembly& a = d->assembly;
    const AssemblyConfiguration c = a.evaluate(a.t_star());
    const double tolerance = 1e-9 * a.model_size();
    std::vector<std::array<Vec3, 4>> places;  // distinct quads, corners sorted
    std::size_t invalid_places = 0, member_faces = 0;
    for (std::size_t m = 0; m < a.member_count(); ++m) {
      for (const Quad& q : a.topology(m).faces()) {
        ++member_faces;
        std::array<Vec3, 4> p{c.members[m][q[0]], c.members[m][q[1]], c.members[m][q[2]], c.members[m][q[3]]};
        const PanelShape shape = panel_shape(p);
        std::sort(p.begin(), p.end(), [](const Vec3& u, const Vec3& v) {
          return std::lexicographical_compare(u.data(), u.data() + 3, v.data(), v.data() + 3);
        });
        const bool seen = std::any_of(places.begin(), places.end(), [&](const std::array<Vec3, 4>& o) {
          for (int i = 0; i < 4; ++i) {
            if ((o[i] - p[i]).norm() > tolerance) return false;
          }
          return true;
        });
        if (seen) continue;
        places.push_back(p);
        invalid_places += is_valid_panel(shape) ? 0 : 1;
      }
    }
    const AssemblyMesh mesh = panel_mesh(*d);
    CAPTURE(k);
    CHECK(mesh.faces.size() == places.size());
    CHECK(mesh.shared_walls == member_faces - places.size());
    CHECK(invalid_panels(*d).size() == invalid_places);
    BuildabilityOptions options;  // panel shapes only: no hints, no sweep of the motion
    options.diagnosis.hints = false;
    options.diagnosis.max_hinted_panels = 0;
    options.sweep_motion = false;  // an aggregate initializer had set bounds.max_growth instead (clang's -Wmissing-braces)
    const BuildabilityReport r = assess_buildability(*d, nullptr, options);
    CHECK(r.panels == places.size());
    CHECK(r.invalid.size() == invalid_places);
    // Merging removes both copies of every shared wall.
    Design merged{a, true, "merged"};
    CHECK(panel_mesh(merged).faces.size() == member_faces - 2 * mesh.shared_walls);
  }
  CHECK(arrays >= 40);
}

TEST_CASE("collision hints at t*: a small step along a hint parts the panels to first order, the whole change often",
          "[buildability]") {
  // The default preset with its apex heights drawn at random: designs whose
  // panels are all simple but cut into each other at t*. A step of 1 % of the
  // first hint's change moves collision_margin_at_t_star by about 1 % of the way
  // to its goal (0 for panels, 10 degrees for a hinge); the whole change (a
  // little more) frees t* in some of them (the margin is not linear).
#ifdef PHEDRA_SANITIZE_BUILD
  const int wanted = 3;
#else
  const int wanted = 12;
#endif
  const json base = json::parse(read_text_file(test::presets + "/default.json"));
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  int tested = 0, freed = 0;
  BuildabilityOptions options;
  options.sweep_motion = false;  // t* alone
  for (int k = 0; k < 400 && tested < wanted; ++k) {
    json preset = base;
    for (json& z : preset["apex_heights"]) z = z.get<double>() + normal(rng);
    std::optional<Design> d;
    try {
      d = design_from_json(preset);
    } catch (const InvalidInputError&) {
      continue;
    }
    const BuildabilityReport r = assess_buildability(*d, &preset, options);
    if (!r.motion.at_t_star || !r.panels_simple() || r.collision_hints.empty()) continue;
    const Collision& c = *r.motion.at_t_star;
    const FieldHint& hint = r.collision_hints.front();
    CAPTURE(k, hint.field, hint.value, hint.change);
    const double goal = c.kind == Collision::Kind::hinge ? collision_hint_opening : 0.0;
    const double before = collision_margin_at_t_star(*d, c);
    auto moved = [&](double fraction) {
      json changed = preset;
      for (const DesignField& field : design_fields(preset, d->assembly.model_size())) {
        if (field.name == hint.field) changed.at(field.pointer) = hint.value + fraction * hint.change;
      }
      return design_from_json(changed);
    };
    const double step = collision_margin_at_t_star(moved(0.01), c) - before;
    CHECK(step / (goal - before) == Approx(0.01).epsilon(0.3));
    try {
      freed += self_intersection_at_t_star(moved(1.2)) ? 0 : 1;
    } catch (const InvalidInputError&) {
    }
    ++tested;
  }
  INFO("hinted collisions " << tested << ", t* free after 1.2 x the change: " << freed);
  CHECK(tested == wanted);
  CHECK(freed * 5 >= tested);
}
