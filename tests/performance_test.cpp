// What the performance work (issue 5) relies on, without timing anything
// (figures come from `phedra bench`): implicit grid lists, the streamed
// construction, the bench cases and the bench report itself.

#include "cli.h"
#include "phedra/bench_cases.h"
#include "phedra/bench_figures.h"
#include "phedra/cache_sizes.h"
#include "phedra/grid_topology.h"
#include "phedra/phedron.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

using namespace phedra;

TEST_CASE("grid lists are computed on demand and agree with their single entries", "[performance]") {
  for (bool cyclic : {false, true}) {
    const GridTopology g(5, 7, cyclic);
    const auto faces = g.faces();
    REQUIRE(faces.size() == g.face_count());
    for (std::size_t k = 0; k < faces.size(); ++k) CHECK(faces[k] == g.face(k));
    CHECK(g.edges().size() == g.edge_count());
    std::set<std::pair<std::size_t, std::size_t>> edges;
    for (const Segment& e : g.edges()) edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
    CHECK(edges.size() == g.edge_count());  // every edge once
    for (const Quad& f : faces) {           // every face side is an edge
      for (int c = 0; c < 4; ++c) {
        const std::size_t a = f[c], b = f[(c + 1) % 4];
        CHECK(edges.count({std::min(a, b), std::max(a, b)}) == 1);
      }
    }
    const auto diagonals = g.diagonals();
    for (std::size_t k = 0; k < faces.size(); ++k) CHECK((diagonals[k] == Segment{faces[k][0], faces[k][2]}));
  }
}

TEST_CASE("the streamed construction equals the nets built whole", "[performance]") {
  const PHedron p(bench::general_open_input(60, 9));
  const AxialNet axial = p.axial_net();
  const ParallelNet parallel = p.parallel_net();
  // reference() is the parallel net with boundary columns, in the user's frame.
  const GridTopology& g = p.topology();
  const std::size_t n = p.profile_vertex_count();
  double worst = 0.0;
  for (std::size_t i = 0; i < g.rows(); ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      worst = std::max(worst, (p.frame().point_to_user(parallel.vertices[i * n + j]) - p.reference()[g.index(i, j + 1)]).norm());
    }
  }
  CHECK(worst <= 1e-12 * p.model_size());
  // evaluate(t*) reproduces the construction.
  const Points at_star = p.evaluate(p.t_star());
  double reproduction = 0.0;
  for (std::size_t k = 0; k < at_star.size(); ++k) reproduction = std::max(reproduction, (at_star[k] - p.reference()[k]).norm());
  CHECK(reproduction <= 1e-12 * p.model_size());
  CHECK(axial.rows == g.rows());
}

TEST_CASE("the bench cases have the sizes they promise", "[performance]") {
  for (std::size_t vertices : {1000, 10000, 100000}) {
    const PHedron p(bench::open_input_with_vertices(vertices));
    CHECK(p.vertex_count() == vertices);
  }
  const Design grid = bench::parallelogram_array(3, 10);
  CHECK(grid.assembly.member_count() == 9);
  const Design panels = bench::open_design_with_panels(1000);
  CHECK(panels.assembly.base().topology().face_count() == 1000);
}

TEST_CASE("phedra bench --quick: every figure finite, the accuracy and closure figures within their targets",
          "[performance]") {
  bench::BenchOptions options;
  options.quick = true;
  std::vector<std::string> announced;
  const bench::BenchReport report = bench::run_benchmarks(options, [&](const std::string& s) { announced.push_back(s); });
  CHECK(announced.size() >= 8);
  std::set<std::string> ids;
  for (const bench::Figure& f : report.figures) {
    CAPTURE(f.id, f.value);
    CHECK(std::isfinite(f.value));
    CHECK(f.value >= 0.0);
    ids.insert(f.id);
    if (f.id.rfind("accuracy.", 0) == 0 || f.id == "closure_check.worst_gap") CHECK(f.met());
  }
  for (const char* id : {"evaluate.ns_per_vertex_1e3", "evaluate.ns_per_vertex_1e5", "write.bandwidth_1e5",
                         "evaluate.linearity", "evaluate.ratio_to_write_in_cache", "interval.ms_1e3", "closure_check.s", "gltf.nodes_s",
                         "gltf.morph_size_ratio", "accuracy.isometry_1e5", "accuracy.isometry_n_1e3",
                         "mechanics.gap_200_tube_s"}) {
    CAPTURE(id);
    CHECK(ids.count(id) == 1);
  }
  const nlohmann::json j = report.to_json();
  CHECK(j["quick"] == true);
  CHECK(j["figures"].size() == report.figures.size());
  std::ostringstream text;
  text << report;
  CHECK(text.str().find("evaluate.linearity") != std::string::npos);
  // No verdict on the targets from small cases.
  CHECK(text.str().find(" met ") == std::string::npos);
  CHECK(text.str().find("MISSED") == std::string::npos);
  CHECK(text.str().find("every target met") == std::string::npos);
  CHECK(text.str().find("quick run: small cases, not compared with the targets") != std::string::npos);
}

TEST_CASE("phedra bench --quick --json -o FILE writes the report, bad options are refused", "[performance][cli]") {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("phedra-bench-" + std::to_string(::getpid()) + ".json");
  std::ostringstream out, err;
  // One group (the whole quick run is the test above).
  CHECK(cli::run({"bench", "--quick", "--only", "evaluate", "--json", "-o", file.string()}, out, err) == 0);
  std::ifstream in(file);
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["figures"].size() >= 5);
  for (const nlohmann::json& f : j["figures"]) {
    const std::string id = f["id"].get<std::string>();
    CHECK((id.rfind("evaluate.", 0) == 0 || id.rfind("write.", 0) == 0));
  }
  CHECK(err.str().find("bench: evaluate(t)") != std::string::npos);
  std::filesystem::remove(file);
  std::ostringstream out3, err3;
  CHECK(cli::run({"bench", "--quick", "--only", "interval", "--json"}, out3, err3) == 0);
  for (const nlohmann::json& f : nlohmann::json::parse(out3.str())["figures"]) CHECK(f["id"].get<std::string>().rfind("interval.", 0) == 0);
  std::ostringstream out4, err4;
  CHECK(cli::run({"bench", "--only", "everything"}, out4, err4) == 2);
  std::ostringstream out2, err2;
  CHECK(cli::run({"bench", "--max-vertices", "10"}, out2, err2) == 2);
  CHECK(err2.str().find("max-vertices") != std::string::npos);
}

TEST_CASE("phedra check --closure-only: closure and shared vertices without the shape figures", "[performance][cli]") {
  const std::string data = PHEDRA_TEST_DATA_DIR, presets = PHEDRA_PRESETS_DIR;
  std::ostringstream out, err;
  CHECK(cli::run({"check", presets + "/grid-3x3.json", "--closure-only", "--json"}, out, err) == 0);
  const nlohmann::json j = nlohmann::json::parse(out.str());
  CHECK(j["passed"] == true);
  CHECK(j["planarity"].is_null());
  CHECK(j["isometry"].is_null());
  CHECK(j["closure"]["relative"].get<double>() <= 1e-9);
  CHECK(j["shared_vertices"]["relative"].get<double>() <= 1e-9);
  // The same figures as the full check.
  std::ostringstream full_out, full_err;
  CHECK(cli::run({"check", presets + "/grid-3x3.json", "--json"}, full_out, full_err) == 0);
  const nlohmann::json full = nlohmann::json::parse(full_out.str());
  CHECK(full["closure"] == j["closure"]);
  CHECK(!full["planarity"].is_null());
  // The asymmetric anti-parallelogram tube still fails, with its gap.
  std::ostringstream bad_out, bad_err;
  CHECK(cli::run({"check", data + "/cases/tube-antiparallelogram-asymmetric.json", "--closure-only"}, bad_out,
                 bad_err) == 1);
  CHECK(bad_out.str().find("not checked (--closure-only)") != std::string::npos);
}

TEST_CASE("the benchmark's cache sizes: sysfs text read, data and unified caches only, defaults when unreadable",
          "[performance]") {
  using bench::parse_cache_size;
  CHECK(parse_cache_size("1024K") == 1048576);
  CHECK(parse_cache_size("32M") == 33554432);
  CHECK(parse_cache_size("2G") == (std::size_t{2} << 30));
  CHECK(parse_cache_size("512") == 512);
  CHECK(parse_cache_size("") == 0);
  CHECK(parse_cache_size("big") == 0);
  CHECK(parse_cache_size("12X") == 0);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("phedra-caches-" + std::to_string(::getpid()));
  auto cache = [&](int index, const char* level, const char* type, const char* size) {
    const std::filesystem::path d = dir / ("index" + std::to_string(index));
    std::filesystem::create_directories(d);
    std::ofstream(d / "level") << level << "\n";
    std::ofstream(d / "type") << type << "\n";
    std::ofstream(d / "size") << size << "\n";
  };
  cache(0, "1", "Data", "48K");
  cache(1, "1", "Instruction", "32K");
  cache(2, "2", "Unified", "2048K");
  cache(3, "3", "Unified", "36864K");
  const bench::CacheSizes sizes = bench::read_cache_sizes(dir);
  CHECK(sizes.measured);
  CHECK(sizes.l2 == 2048u * 1024u);
  CHECK(sizes.last_level == 36864u * 1024u);
  std::filesystem::remove_all(dir);
  const bench::CacheSizes none = bench::read_cache_sizes(dir);  // gone: the defaults, said so
  CHECK_FALSE(none.measured);
  CHECK(none.l2 == 1u << 20);
  CHECK(none.last_level == 32u << 20);
}
