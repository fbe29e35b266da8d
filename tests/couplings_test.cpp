// Couplings and tube arrays: every cell closed and shared vertices together over
// the interval; the same cell reached by different coupling paths is the same at
// every t; merging removes exactly the shared strips and keeps the mesh manifold.

#include "phedra/assembly_check.h"
#include "phedra/assembly_mesh.h"
#include "phedra/coupling.h"
#include "phedra/design.h"
#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/preset.h"
#include "phedra/tube.h"
#include "phedra/tube_array.h"
#include "support/random_input.h"
#include "phedra/design_preset.h"
#include "phedra/check_report.h"

#include <catch2/catch.hpp>

#include <map>
#include <optional>
#include <set>

using namespace phedra;
using Catch::Matchers::Contains;

using phedra::test::uniform;

namespace {

/// Heights of the two line families: u increasing, w decreasing and above u, so
/// every grid vertex lies on the base vertex's side of the axis.
void random_families(std::mt19937_64& rng, std::size_t rows, std::size_t columns, std::vector<double>& u,
                     std::vector<double>& w) {
  u = {uniform(rng, -3, -2)};
  for (std::size_t a = 0; a < rows; ++a) u.push_back(u.back() + uniform(rng, 0.3, 0.8));
  w = {uniform(rng, 2.5, 3.5)};
  for (std::size_t b = 0; b < columns; ++b) w.push_back(w.back() - uniform(rng, 0.3, 0.7));
}

std::optional<TubeGrid> random_grid(std::mt19937_64& rng, std::size_t rows, std::size_t columns) {
  for (int attempt = 0; attempt < 500; ++attempt) {
    test::RandomInputShape shape;
    shape.strips = 2 + static_cast<std::size_t>(uniform(rng, 0, 14));
    shape.profile_vertices = 5;
    shape.smooth = true;
    std::vector<double> u, w;
    random_families(rng, rows, columns, u, w);
    try {
      ControlPolylines base = test::random_input(rng, shape);
      // Heights are relative to the base vertex's height along the axis.
      const double h = base.trajectory[0].dot(base.axis);
      for (double& x : u) x += h;
      for (double& x : w) x += h;
      TubeGrid grid = make_parallelogram_grid(base, u, w);
      const FlexionInterval& f = grid.assembly.flexion_interval();
      if (test::well_inside_interval(grid.assembly.t_star(), f.lower.t, f.upper.t, grid.assembly.model_size())) {
        return grid;
      }
    } catch (const InvalidInputError&) {
    }
  }
  return std::nullopt;
}

/// Cell positions as a set-independent signature: the sorted list of its row-0..m vertex positions.
Points cell_vertices(const Assembly& a, const AssemblyConfiguration& c, std::size_t member) {
  Points v = c.members[member];
  std::sort(v.begin(), v.end(), [](const Vec3& p, const Vec3& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  });
  (void)a;
  return v;
}

double set_distance(Points a, Points b) {
  // Greedy nearest matching (cells have well separated vertices).
  double worst = 0;
  for (const Vec3& p : a) {
    double best = INFINITY;
    for (const Vec3& q : b) best = std::min(best, (p - q).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

Design design(const std::string& preset) {
  return load_design(std::string(PHEDRA_PRESETS_DIR) + "/" + preset + ".json");
}

}  // namespace

TEST_CASE("random 2D arrays: every cell closed, shared vertices together over the interval", "[couplings]") {
  std::mt19937_64 rng(2026);
  for (int k = 0; k < 24; ++k) {
    const std::size_t rows = 1 + k % 3, columns = 1 + (k / 3) % 3;
    CAPTURE(k, rows, columns);
    std::optional<TubeGrid> grid = random_grid(rng, rows, columns);
    REQUIRE(grid.has_value());
    const Assembly& a = grid->assembly;
    CHECK(a.member_count() == rows * columns);
    // Shared vertex lines: (rows+1)(columns+1) grid lines, each in 1..4 cells.
    const std::size_t lines = (rows + 1) * (columns + 1);
    const std::size_t single = 4;  // the outer corners belong to one cell only
    const std::size_t profiles = a.base().topology().rows();
    if (rows * columns > 1) CHECK(a.shared_vertices().size() == (lines - single) * profiles);
    CheckOptions options;
    options.samples = 60;
    const AssemblyCheckReport r = check_assembly(a, options);
    CAPTURE(report_json(r).dump());
    CHECK(r.passed());
    CHECK(r.closure.value <= 1e-9 * r.model_size);
    CHECK(r.shared.value <= 1e-9 * r.model_size);
    for (std::size_t m = 0; m < a.member_count(); ++m) CHECK(r.member_closure[m] <= 1e-9 * r.model_size);
  }
}

TEST_CASE("the same cell reached by different coupling paths is the same at every t", "[couplings]") {
  std::mt19937_64 rng(99);
  for (int k = 0; k < 10; ++k) {
    CAPTURE(k);
    std::optional<TubeGrid> grid = random_grid(rng, 2, 2);
    REQUIRE(grid.has_value());
    Assembly& a = grid->assembly;
    const std::size_t via_column = grid->cell[1][1];  // (0,0) -> (0,1) -> (1,1)
    const std::vector<double> h = a.apex_heights(0);   // (u0, w0, u1, w1, u0, w0)
    const std::vector<double> cell11 = a.apex_heights(via_column);
    // (0,0) -> (1,0) -> (1,1): cell (1,0) has its side on w_1 as side 3.
    const std::size_t via_row = a.add_member(face_coupling(a, grid->cell[1][0], 3, cell11[0], "via row"));
    // (0,0) -> (1,1) directly by edge-sharing at the common vertex (1,1) = vertex 2 of cell (0,0).
    const std::vector<double> u2w2{a.apex_heights(grid->cell[1][0])[3], a.apex_heights(grid->cell[0][1])[3]};
    const std::size_t via_edge = a.add_member(edge_sharing(a, 0, 2, u2w2, "via edge"));
    check_edge_sharing_rays(a, via_edge, "via edge");
    for (double f : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
      const AssemblyConfiguration c = a.evaluate(a.t_at_fraction(f));
      const Points reference = cell_vertices(a, c, via_column);
      CHECK(set_distance(reference, cell_vertices(a, c, via_row)) <= 1e-9 * a.model_size());
      CHECK(set_distance(reference, cell_vertices(a, c, via_edge)) <= 1e-9 * a.model_size());
    }
  }
}

TEST_CASE("merging removes exactly the shared strips and keeps the mesh manifold", "[couplings]") {
  for (const std::string preset : {"merged-tube", "row-of-cells", "grid-3x3"}) {
    CAPTURE(preset);
    const Design d = design(preset);
    const Assembly& a = d.assembly;
    const AssemblyMesh separate = separate_mesh(a);
    const AssemblyMesh merged = merged_mesh(a);
    const std::size_t strips = a.base().topology().rows() - 1;
    // Shared sides: a row of c cells has c-1, an r x c grid r(c-1) + c(r-1).
    std::size_t shared_sides = a.member_count() - 1;
    if (preset == "grid-3x3") shared_sides = 3 * 2 + 3 * 2;
    CHECK(merged.deleted_faces == 2 * shared_sides * strips);
    CHECK(merged.faces.size() + merged.deleted_faces == separate.faces.size());
    // Manifold: every edge in at most two faces, boundary edges only on the first and last profile.
    std::map<std::pair<std::size_t, std::size_t>, int> uses;
    for (const Quad& q : merged.faces) {
      for (int e = 0; e < 4; ++e) {
        const std::size_t x = q[e], y = q[(e + 1) % 4];
        ++uses[{std::min(x, y), std::max(x, y)}];
      }
    }
    for (const auto& [edge, count] : uses) {
      CHECK(count <= 2);
      if (count == 1) {
        const VertexRef& r0 = merged.vertices[edge.first];
        const VertexRef& r1 = merged.vertices[edge.second];
        const std::size_t row0 = a.topology(r0.member).row_of(r0.vertex), row1 = a.topology(r1.member).row_of(r1.vertex);
        CHECK(row0 == row1);
        CHECK((row0 == 0 || row0 == strips));
      }
    }
    // The merged tube is one closed loop of sides per profile: boundary edges = 2 x sides.
    std::size_t boundary = 0;
    for (const auto& [edge, count] : uses) boundary += count == 1;
    CHECK(boundary * strips == 2 * merged.faces.size());
    // Welded: no two mesh vertices at the same place at t*.
    const Points at_star = merged.positions(a.evaluate(a.t_star()));
    std::set<std::array<long long, 3>> cells;
    for (const Vec3& p : at_star) {
      cells.insert({std::llround(p.x() * 1e6), std::llround(p.y() * 1e6), std::llround(p.z() * 1e6)});
    }
    CHECK(cells.size() == at_star.size());
  }
}

TEST_CASE("coupling errors: anti-parallelogram face coupling, overlapping edge-sharing, bad indices", "[couplings]") {
  const Design anti = design("anti-parallelogram-tube");
  CHECK_THROWS_WITH(face_coupling(anti.assembly, 0, 1, std::nullopt, "couplings[0]"),
                    Contains("couplings[0]") && Contains("the parent cell itself"));
  Design par = design("parallelogram-tube");
  CHECK_THROWS_WITH(face_coupling(par.assembly, 0, 1, std::nullopt, "f"), Contains("needs its free apex height"));
  CHECK_THROWS_WITH(face_coupling(par.assembly, 0, 4, 1.0, "f"), Contains("side must be 0..3"));
  CHECK_THROWS_WITH(face_coupling(par.assembly, 3, 1, 1.0, "f"), Contains("parent 3 does not exist"));
  CHECK_THROWS_WITH(edge_sharing(par.assembly, 0, 1, {1.0}, "e"), Contains("two free heights"));
  // Free heights that put the new cell on the parent's side of the hinge.
  const std::vector<double> h = par.assembly.apex_heights(0);
  const std::size_t overlapping = par.assembly.add_member(edge_sharing(par.assembly, 0, 2, {h[0] + 0.1, h[1] - 0.1}, "e"));
  CHECK_THROWS_WITH(check_edge_sharing_rays(par.assembly, overlapping, "couplings[0]"),
                    Contains("opposite to the parent's sides"));
  const Design open = design("default");
  CHECK_THROWS_WITH(face_coupling(open.assembly, 0, 1, 1.0, "f"), Contains("is not a quad tube"));
  // An anti-parallelogram edge-sharing cell takes one free height and stays closed.
  const ControlPolylines base = load_preset(std::string(PHEDRA_PRESETS_DIR) + "/default.json");
  const Assembly anti_tube(make_tube(base, TubeType::anti_parallelogram, {-0.5, -2.0, 0.5, 2.0}));
  bool found = false;
  for (double t2 = -3.0; t2 <= 3.0 && !found; t2 += 0.5) {
    Assembly trial = anti_tube;
    try {
      const std::size_t m = trial.add_member(edge_sharing(trial, 0, 1, {t2}, "e"));
      check_edge_sharing_rays(trial, m, "e");
      const AssemblyCheckReport r = check_assembly(trial, {});
      CHECK(r.passed());
      found = true;
    } catch (const InvalidInputError&) {
    }
  }
  CHECK(found);
}

TEST_CASE("design presets: keys and their errors", "[couplings]") {
  auto failure = [](const std::string& text) {
    try {
      design_from_json(nlohmann::json::parse(text));
    } catch (const InvalidInputError& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  const std::string where = R"("trajectory": [[2,0,0],[1.2,1.5,0.4],[0.1,2.3,0.9]], "directions": [[1,0,0],[1.2,1.5,0],[-0.2,1,0]])";
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "parallelogram", "apex_heights": [1, 2, 3]}})"),
             Contains("tube.apex_heights: expected 4 heights"));
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "square", "apex_heights": [1, 2, 3, 4]}})"),
             Contains("tube.type"));
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "parallelogram", "apex_heights": [-1, 2, -2, 3], "x": 1}})"),
             Contains("tube.x: unknown key"));
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "parallelogram", "apex_heights": [-1, 2, -2, 3]}, "signs": "+"})"),
             Contains("signs: not allowed together with \"tube\""));
  CHECK_THAT(failure("{" + where + R"(, "grid": {"u_heights": [-1], "w_heights": [2, 3]}})"),
             Contains("grid.u_heights: needs at least 2 heights"));
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "parallelogram", "apex_heights": [-1, 2, -2, 3]}, "couplings": [{"type": "glue"}]})"),
             Contains("couplings[0].type"));
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "parallelogram", "apex_heights": [-1, 2, -2, 3]}, "merge": true})"),
             Contains("merge: needs face-coupled members"));
  CHECK_THAT(failure("{" + where + R"(})"), Contains("apex_heights: missing"));
  CHECK_THAT(failure("{" + where + R"(, "tube": {"type": "parallelogram", "apex_heights": [-1, 2, -2, 3]}, "row": {"side": 1, "free_heights": [-2]}})"),
             Contains("row, cell 1") && Contains("pairwise distinct"));
}
