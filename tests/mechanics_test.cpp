// Mechanics (issue 36): the hinge angle and its derivatives, the bar-and-hinge
// model's rules, the stiffness's modes against the exact motion.

#include "support/random_input.h"
#include "support/test_files.h"
#include "phedra/bar_hinge_model.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/hinge_angle.h"
#include "phedra/stiffness_modes.h"
#include "phedra/energy_landscape.h"
#include "phedra/homogenized_strain.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/mechanics_figures.h"
#include "phedra/bench_cases.h"
#include "phedra/chart.h"
#include "support/cli_run.h"
#include "../mechanics/src/vector_atan2.h"  // atan2_many (internal to mechanics/)
#include "../mechanics/src/dense_svd.h"     // right_singular (internal to mechanics/)
#include "../mechanics/src/fold_kernel.h"   // FoldKernel (internal to mechanics/)
#include "../mechanics/src/block_assembly.h"  // BlockAssembly (internal to mechanics/)
#include "../mechanics/src/vertex_nodes.h"    // vertex_nodes (internal to mechanics/)
#include "../mechanics/src/node_cholesky.h"   // NodeCholesky (internal to mechanics/)
#include "../mechanics/src/block_lanczos.h"   // block_lanczos_largest (internal to mechanics/)
#include "../mechanics/src/cholmod_memory.h"  // reports_free_pages (internal to mechanics/)

#include <catch2/catch.hpp>
#include <Spectra/SymEigsShiftSolver.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <numbers>
#include <set>
#include <vector>

using namespace phedra;

namespace {

const double pi = std::numbers::pi;

/// Hinge [j k i l] on the x axis, wing i at angle 0 in the xy plane, wing l
/// turned by `dihedral` about the axis (pi: flat), then moved off the axes.
HingeNodes hinge_at(double dihedral, std::mt19937_64& rng) {
  const Vec3 j(0, 0, 0), k(1.3, 0, 0);
  const Vec3 i(0.4, 0.9, 0);
  const Vec3 l(0.7, 0.8 * std::cos(dihedral), 0.8 * std::sin(dihedral));
  const Mat3 r = Eigen::Quaterniond(Eigen::Vector4d(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1),
                                                     test::uniform(rng, -1, 1), test::uniform(rng, -1, 1)).normalized())
                     .toRotationMatrix();
  const Vec3 shift(test::uniform(rng, -2, 2), test::uniform(rng, -2, 2), test::uniform(rng, -2, 2));
  return {r * j + shift, r * k + shift, r * i + shift, r * l + shift};
}

Vec3& node(HingeNodes& x, int a) { return a == 0 ? x.j : a == 1 ? x.k : a == 2 ? x.i : x.l; }

/// MERLIN2's FoldKe: sign(n . r_ij) acos(m . n / |m| |n|), in [0, 2 pi).
double merlin_angle(const HingeNodes& x) {
  const Vec3 rkj = x.k - x.j, rij = x.i - x.j, rkl = x.k - x.l;
  const Vec3 m = rij.cross(rkj), n = rkj.cross(rkl);
  const double s = std::abs(n.dot(rij)) > 1e-8 ? (n.dot(rij) > 0 ? 1.0 : -1.0) : 1.0;
  double he = s * std::acos(std::clamp(m.dot(n) / (m.norm() * n.norm()), -1.0, 1.0));
  return he < 0 ? he + 2 * pi : he;
}

/// A design's bar-and-hinge model at 0.4 of its flexion interval.
BarHingeModel model_at_04(const Design& design, PanelModel panels) {
  StiffnessOptions options;
  options.panels = panels;
  return BarHingeModel(design, design.assembly.evaluate(design.assembly.t_at_fraction(0.4)), options);
}

/// The energy landscape's options with the rest state at `fraction` of the
/// flexion interval, n4b5 panels (every preset takes them).
EnergyOptions rest_at(const Design& design, double fraction) {
  EnergyOptions o;
  o.rest_t = design.assembly.t_at_fraction(fraction);
  o.stiffness.panels = PanelModel::n4b5;
  return o;
}

}  // namespace

TEST_CASE("hinge angle: pi flat, MERLIN2's value, continuous across 0 and 2 pi", "[mechanics]") {
  std::mt19937_64 rng(5);
  for (double dihedral : {pi, pi - 1e-9, pi + 1e-9, 0.3, 1.0, 2.5, 4.0, 5.9}) {
    const HingeNodes x = hinge_at(dihedral, rng);
    const double theta = hinge_angle(x);
    CHECK(theta >= 0.0);
    CHECK(theta < 2 * pi);
    CHECK(std::abs(theta - merlin_angle(x)) < 1e-7);
    // The wing i turned by `dihedral` from l about the axis: theta is dihedral or 2 pi - dihedral.
    CHECK(std::min(std::abs(theta - dihedral), std::abs(theta - (2 * pi - dihedral))) < 1e-12);
  }
  CHECK(hinge_angle(hinge_at(pi, rng)) == Approx(pi).margin(1e-14));
  CHECK(continuous_angle(0.01, 6.2) == Approx(0.01 + 2 * pi));
  CHECK(continuous_angle(6.27, 0.02) == Approx(6.27 - 2 * pi));
  CHECK(continuous_angle(3.0, 3.1) == 3.0);
}

TEST_CASE("hinge angle gradient and Hessian against differences: flat, nearly flat and folded", "[mechanics]") {
  std::mt19937_64 rng(17);
  for (double dihedral : {pi, pi + 1e-7, pi - 1e-4, 2.0, 0.35, 5.5, 3.9}) {
    INFO("dihedral " << dihedral);
    const HingeNodes x = hinge_at(dihedral, rng);
    const std::array<Vec3, 4> g = hinge_angle_gradient(x);
    const Eigen::Matrix<double, 12, 12> h = hinge_angle_hessian(x);
    const double step = 1e-6;
    double gradient_error = 0.0, hessian_error = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int c = 0; c < 3; ++c) {
        HingeNodes plus = x, minus = x;
        node(plus, a)(c) += step;
        node(minus, a)(c) -= step;
        const double d = continuous_angle(hinge_angle(plus), hinge_angle(x)) -
                         continuous_angle(hinge_angle(minus), hinge_angle(x));
        gradient_error = std::max(gradient_error, std::abs(d / (2 * step) - g[a](c)));
        const std::array<Vec3, 4> gp = hinge_angle_gradient(plus), gm = hinge_angle_gradient(minus);
        for (int b = 0; b < 4; ++b) {
          for (int e = 0; e < 3; ++e) {
            const double fd = (gp[b](e) - gm[b](e)) / (2 * step);
            hessian_error = std::max(hessian_error, std::abs(fd - h(3 * b + e, 3 * a + c)));
          }
        }
      }
    }
    CHECK(gradient_error < 1e-8);
    CHECK(hessian_error < 1e-7);
    CHECK((h - h.transpose()).cwiseAbs().maxCoeff() < 1e-12);
    // A rigid motion does not change the angle: the gradient is orthogonal to it.
    Vec3 sum = Vec3::Zero(), moment = Vec3::Zero();
    for (int a = 0; a < 4; ++a) {
      sum += g[a];
      moment += node(const_cast<HingeNodes&>(x), a).cross(g[a]);
    }
    CHECK(sum.norm() < 1e-12);
    CHECK(moment.norm() < 1e-11);
  }
}

/// Whether every panel of the design is convex at t (n5b8 needs it).
bool n5b8_models(const Design& design, double t) {
  try {
    BarHingeModel(design, design.assembly.evaluate(t), StiffnessOptions{});
    return true;
  } catch (const InvalidInputError& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("not convex") && Catch::Matchers::Contains("--panels n4b5"));
    return false;
  }
}

TEST_CASE("every shipped preset: six rigid-body modes, and with stiff panels the first mode is the motion", "[mechanics]") {
  std::size_t refused = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    const std::string name = entry.path().filename().string();
    const Design design = load_design(entry.path());
    const auto& interval = design.assembly.flexion_interval();
    for (const PanelModel panels : {PanelModel::n4b5, PanelModel::n5b8}) {
      StiffnessOptions stiff;  // KB / KF = 1e5
      stiff.panels = panels;
      stiff.bar = 1e5;
      stiff.bend = 1000.0;
      stiff.fold = 0.01;
      for (double f : {0.25, 0.5, 0.75}) {
        INFO(name << " " << to_string(panels) << " at fraction " << f);
        const double t = interval.lower.t + f * (interval.upper.t - interval.lower.t);
        if (panels == PanelModel::n5b8 && !n5b8_models(design, t)) {
          ++refused;
          continue;
        }
        const ModeAnalysis a = analyze_modes(design, t, stiff, 2);
        CHECK(a.rigid_body_modes == 6);
        REQUIRE(a.motion_alignment);
        CHECK(*a.motion_alignment >= 0.9999);
      }
    }
  }
  CHECK(refused == 3);  // the anti-parallelogram edge pair (16 bow-ties), at each fraction
}


TEST_CASE("the softer panels' alignment: a second hinge mode mixes in, the motion in the span of two", "[mechanics]") {
  // The issue's figures: KB / KF = 10 (the defaults) on the parallelogram tube and grid-3x3.
  for (const char* name : {"parallelogram-tube.json", "grid-3x3.json"}) {
    const Design design = load_design(std::filesystem::path(test::presets) / name);
    for (double f : {0.25, 0.5, 0.75}) {
      INFO(name << " at " << f);
      const ModeAnalysis a = analyze_modes(design, design.assembly.t_at_fraction(f), StiffnessOptions{}, 2);
      CHECK(*a.motion_alignment > 0.7);
      CHECK(*a.motion_alignment < 0.97);
      CHECK(a.motion_in_span[1] >= 0.9999);
    }
  }
}

TEST_CASE("the model's counts and rules: triangles, shared walls, T-junctions, n4b5 diagonals", "[mechanics]") {
  // The default preset has two welded quads (triangle panels); grid-3x3's interior vertex lines
  // are shared by four walls: 4 * 3 / 2 = 6 fold hinges there.
  const Design open = load_design(std::filesystem::path(test::presets) / "default.json");
  const BarHingeModel m(open, open.assembly.evaluate(open.assembly.t_star()), StiffnessOptions{});
  CHECK(m.triangle_panels() == 2);
  CHECK(m.node_count() == m.corner_node_count() + m.panels().size() - 2);  // a centre a quad
  CHECK(m.bend_count() == 4 * (m.panels().size() - 2));
  const Design grid = load_design(std::filesystem::path(test::presets) / "grid-3x3.json");
  StiffnessOptions n4b5;
  n4b5.panels = PanelModel::n4b5;
  const BarHingeModel g(grid, grid.assembly.evaluate(grid.assembly.t_star()), n4b5);
  std::map<std::pair<std::size_t, std::size_t>, int> per_edge;
  for (std::size_t h = 0; h < g.fold_count(); ++h) {
    const Hinge& hinge = g.hinges()[h];
    ++per_edge[std::minmax(hinge.nodes[0], hinge.nodes[1])];
    CHECK(hinge.panels[0] < hinge.panels[1]);
  }
  std::map<int, int> histogram;
  for (const auto& [edge, count] : per_edge) ++histogram[count];
  CHECK(histogram.count(6) == 1);  // edges of four panels
  CHECK(histogram[6] > 0);
  CHECK(g.bend_count() == g.panels().size());  // one diagonal a quad
  CHECK(g.bars().size() == per_edge.size() + g.bend_count() +
                               [&] {  // boundary edges (one panel)
                                 std::set<std::pair<std::size_t, std::size_t>> all;
                                 for (const ModelPanel& p : g.panels())
                                   for (std::size_t k = 0; k < p.corners.size(); ++k)
                                     all.insert(std::minmax(p.corners[k], p.corners[(k + 1) % p.corners.size()]));
                                 return all.size() - per_edge.size();
                               }());
  // Every hinge of a flat-at-rest panel (bending) is at pi; every fold angle in [0, 2 pi).
  for (std::size_t h = 0; h < g.hinges().size(); ++h) {
    const double theta = g.angle(h, g.positions());
    if (g.hinges()[h].kind == HingeKind::bend) CHECK(std::abs(theta - pi) < 1e-9);
    CHECK(theta >= 0.0);
    CHECK(theta < 2 * pi);
  }
}

TEST_CASE("the fold angles' atan2 in bulk equals std::atan2 in every quadrant and tail length", "[mechanics]") {
  // atan2_many takes glibc's vector atan2 (eight or four at a time) where the processor has
  // AVX-512 or AVX2: a wrong calling convention there gives garbage, not a small error.
  std::mt19937_64 rng(36);
  for (std::size_t n = 0; n <= 41; ++n) {
    std::vector<double> y(n), x(n), out(n, -7.0);
    for (std::size_t h = 0; h < n; ++h) {
      const double r = std::pow(10.0, test::uniform(rng, -8, 8));
      const double a = test::uniform(rng, -pi, pi);
      y[h] = r * std::sin(a);
      x[h] = h % 7 == 3 ? 0.0 : r * std::cos(a);
    }
    atan2_many(y.data(), x.data(), out.data(), n);
    for (std::size_t h = 0; h < n; ++h) {
      const double exact = std::atan2(y[h], x[h]);
      INFO("n " << n << " h " << h << " y " << y[h] << " x " << x[h]);
      CHECK(std::abs(out[h] - exact) <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(exact)));
    }
  }
}

#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
namespace phedra {
void atan2_avx2(const double* y, const double* x, double* out, std::size_t n);
void atan2_avx512(const double* y, const double* x, double* out, std::size_t n);
}  // namespace phedra

TEST_CASE("glibc's eight-wide vector atan2 gives the four-wide one's bits", "[mechanics]") {
  // atan2_many takes the eight-wide one where the processor has AVX-512 and the
  // four-wide one elsewhere (and for a block's last four): the energy's samples
  // evaluated four together equal each alone only if a fold's angle does not
  // depend on which of them made it. Flat folds (y = +-0 or tiny, x = -1), zeros,
  // and ratios from 1e-300 to 1e300.
  if (!(__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx2") &&
        __builtin_cpu_supports("fma"))) {
    WARN("no AVX-512 here: nothing to compare");
    return;
  }
  std::mt19937_64 rng(37);
  const std::size_t n = 1 << 16;
  std::vector<double> y(n), x(n), four(n), eight(n);
  for (std::size_t h = 0; h < n; ++h) {
    const double r = std::pow(10.0, test::uniform(rng, -150, 150)), a = test::uniform(rng, -pi, pi);
    y[h] = r * std::sin(a), x[h] = std::pow(10.0, test::uniform(rng, -150, 150)) * std::cos(a);
    if (h % 11 == 0) y[h] = h % 2 ? 0.0 : -0.0, x[h] = -1.0;
    if (h % 13 == 0) y[h] = std::copysign(1e-17, test::uniform(rng, -1, 1)), x[h] = -1.0;
    if (h % 17 == 0) x[h] = h % 2 ? 0.0 : -0.0;
  }
  atan2_avx2(y.data(), x.data(), four.data(), n);
  atan2_avx512(y.data(), x.data(), eight.data(), n);
  std::size_t different = 0;
  for (std::size_t h = 0; h < n; ++h) different += std::memcmp(&four[h], &eight[h], sizeof(double)) != 0;
  CHECK(different == 0);
}
#endif

TEST_CASE("the energy's fold kernel (panel normals) equals MERLIN2's angle and its gradient times the rates", "[mechanics]") {
  // The kernel takes each fold's angle from its panels' unit normals (planar at
  // every t): the same number as hinge_angle's formula from the wing nodes, and
  // its rate the same as hinge_angle_gradient . dX/dt, on every shipped preset
  // and the array with T-junctions, both panel models, at and away from the model's t.
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "preset.schema.json") files.push_back(entry.path());
  }
  std::size_t folds = 0;
  for (const auto& file : files) {
    const Design design = load_design(file);
    const auto& interval = design.assembly.flexion_interval();
    auto at = [&](double f) { return interval.lower.t + f * (interval.upper.t - interval.lower.t); };
    for (const PanelModel panels : {PanelModel::n4b5, PanelModel::n5b8}) {
      StiffnessOptions options;
      options.panels = panels;
      if (panels == PanelModel::n5b8 && !n5b8_models(design, at(0.4))) continue;
      const BarHingeModel model(design, design.assembly.evaluate(at(0.4)), options);
      const FoldKernel kernel(model);
      for (double f : {0.4, 0.02, 0.7, 0.98}) {
        INFO(file.filename().string() << " " << to_string(panels) << " at fraction " << f);
        AssemblyConfiguration c;
        std::vector<Points> rates;
        REQUIRE(design.assembly.evaluate_rate(at(f), c, rates));
        Points x, v, corners, corner_rates;
        model.node_positions(c, x);
        model.node_rates(rates, v);
        model.mesh().nodes(c.members, corners);
        model.mesh().nodes(rates, corner_rates);
        const std::size_t n = kernel.size();
        std::vector<double> theta(n), rate(n), frames;
        kernel.angles(corners, &corner_rates, theta.data(), rate.data(), frames);
        double speed = 0.0;
        for (const Vec3& w : v) speed = std::max(speed, w.norm());
        for (std::size_t h = 0; h < n; ++h) {
          const Hinge& hinge = model.hinges()[h];
          const HingeNodes nodes = hinge_nodes(hinge, x);
          const double merlin = hinge_angle(nodes);
          CHECK(std::abs(std::remainder(theta[h] - merlin, 2 * pi)) <= 1e-11);
          const std::array<Vec3, 4> g = hinge_angle_gradient(nodes);
          double exact = 0.0;
          for (int q = 0; q < 4; ++q) exact += g[q].dot(v[hinge.nodes[q]]);
          // Rounding: the gradient's size (1 / the wing's distance) times the nodes' speed.
          double scale = 0.0;
          for (int q = 0; q < 4; ++q) scale = std::max(scale, g[q].norm());
          CHECK(std::abs(rate[h] - exact) <= 1e-10 * scale * speed);
        }
        folds += n;
      }
    }
  }
  CHECK(folds > 5000);
}

TEST_CASE("the energy's samples evaluated four together equal each evaluated alone, bit for bit", "[mechanics]") {
  // FoldEnergy::load_lanes and evaluate_lanes (the landscape's walk, SIMD across
  // samples: the members' recursions, the nodes' writes, the fold kernel) against
  // evaluate() of each lane from the lane before it: E, dE/dt, the largest turn,
  // every angle, turn, node position and rate, and the strain from the nodes; on
  // every shipped preset (open P-hedra, tubes, arrays with boundary columns and
  // T-junctions), both panel models, steps small and large (folds turning past
  // half a turn between lanes).
  std::vector<std::filesystem::path> files{std::filesystem::path(test::data) / "bistable.json"};
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "preset.schema.json") files.push_back(entry.path());
  }
  std::size_t lanes_checked = 0;
  for (const auto& file : files) {
    const Design design = load_design(file);
    for (const PanelModel panels : {PanelModel::n4b5, PanelModel::n5b8}) {
      StiffnessOptions options;
      options.panels = panels;
      const double rest = design.assembly.t_at_fraction(0.5);
      if (panels == PanelModel::n5b8 && !n5b8_models(design, rest)) continue;
      const FoldEnergy fold(design, rest, options);
      for (const double step : {0.01, 0.2}) {
        INFO(file.filename().string() << " " << to_string(panels) << " step " << step);
        std::array<double, FoldEnergy::lanes> ts;
        for (std::size_t l = 0; l < ts.size(); ++l) ts[l] = design.assembly.t_at_fraction(0.1 + step * static_cast<double>(l));
        FoldEnergy::Scratch together, alone;
        REQUIRE(fold.load_lanes(ts.data(), together));
        std::vector<double> near;
        fold.evaluate(design.assembly.t_at_fraction(0.08), {}, near, alone);
        std::array<std::vector<double>, FoldEnergy::lanes> angles;
        const auto values = fold.evaluate_lanes(near, angles, together);
        const HomogenizedStrain strain(design.assembly, MetricsAxes::structural);
        const std::optional<std::vector<std::uint32_t>> at_nodes = vertex_nodes(fold, rest);
        REQUIRE(at_nodes);
        const Points weights = strain.weights(*at_nodes, fold.model().corner_node_count());
        std::array<HomogenizedStrain::State, FoldEnergy::lanes> strains;
        strain.states_of_lanes(together.lane_x.data(), together.lane_v.data(), weights, strains.data());
        for (std::size_t l = 0; l < ts.size(); ++l) {
          std::vector<double> single;
          const FoldEnergy::Value v = fold.evaluate(ts[l], near, single, alone);
          CHECK(values[l].energy == v.energy);
          REQUIRE(values[l].rate);
          REQUIRE(v.rate);
          CHECK(*values[l].rate == *v.rate);
          CHECK(values[l].largest_turn == v.largest_turn);
          CHECK(angles[l] == single);
          CHECK(together.lane_turns[l] == alone.turns);
          near = single;
          // The nodes as nodes_at leaves them, and the strain from them.
          for (std::size_t i = 0; i < alone.x.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
              const std::size_t at = (3 * i + static_cast<std::size_t>(c)) * FoldEnergy::lanes + l;
              CHECK(together.lane_x[at] == alone.x[i][c]);
              CHECK(together.lane_v[at] == alone.v[i][c]);
            }
          }
          CHECK(strains[l].stretch == strain.state_of(alone.x, &alone.v, weights).stretch);
          CHECK(strains[l].rate == strain.state_of(alone.x, &alone.v, weights).rate);
          ++lanes_checked;
        }
      }
    }
  }
  CHECK(lanes_checked > 40);
}

TEST_CASE("the stiffness's block assembly equals the upper triangle of a dense sum of the same blocks, repeated nodes and empty columns too",
          "[mechanics]") {
  std::mt19937_64 rng(3606);
  for (int round = 0; round < 20; ++round) {
    const std::size_t nodes = 1 + static_cast<std::size_t>(test::uniform(rng, 0, 30));
    std::vector<std::vector<std::size_t>> elements(static_cast<std::size_t>(test::uniform(rng, 0, 40)));
    for (auto& e : elements) {
      e.resize(static_cast<std::size_t>(test::uniform(rng, 1, 5)));
      for (auto& v : e) v = static_cast<std::size_t>(test::uniform(rng, 0, static_cast<double>(nodes) - 1e-9));
    }
    std::vector<std::span<const std::size_t>> spans(elements.begin(), elements.end());
    BlockAssembly k(nodes, spans);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(nodes), 3 * static_cast<Eigen::Index>(nodes));
    for (const auto& e : elements) {
      for (std::size_t r : e) {
        for (std::size_t c : e) {
          if (r > c) continue;  // the upper triangle's blocks only
          const Mat3 block = Mat3::Random();
          k.add(r, c, block);
          dense.block<3, 3>(3 * static_cast<Eigen::Index>(r), 3 * static_cast<Eigen::Index>(c)) += block;
        }
      }
    }
    const Eigen::SparseMatrix<double> sparse = k.upper();
    REQUIRE(sparse.isCompressed());
    const Eigen::MatrixXd expected = dense.triangularView<Eigen::Upper>();
    CHECK((Eigen::MatrixXd(sparse) - expected).cwiseAbs().maxCoeff() <= 1e-12);
    // Nothing below the diagonal is stored.
    for (Eigen::Index c = 0; c < sparse.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(sparse, c); it; ++it) CHECK(it.row() <= c);
    }
  }
}

TEST_CASE("the stiffness's Cholesky factor solves K + shift I (one and four right-hand sides): random node graphs and K itself, against a dense solve",
          "[mechanics]") {
  std::mt19937_64 rng(3607);
  const auto check = [](const Eigen::SparseMatrix<double>& a, double shift) {
    const NodeCholesky factor(a, shift);  // a's upper triangle read (a whole or only that triangle)
    const Eigen::SparseMatrix<double> symmetric = a.selfadjointView<Eigen::Upper>();
    const Eigen::MatrixXd dense = Eigen::MatrixXd(symmetric) + shift * Eigen::MatrixXd::Identity(a.rows(), a.cols());
    const Eigen::LLT<Eigen::MatrixXd> llt(dense);
    REQUIRE(llt.info() == Eigen::Success);
    for (int rhs = 0; rhs < 2; ++rhs) {
      const Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
      Eigen::VectorXd x(a.rows());
      factor.solve(b.data(), x.data());
      const Eigen::VectorXd expected = llt.solve(b);
      CHECK((x - expected).norm() <= 1e-9 * expected.norm());
      factor.solve(b.data(), const_cast<double*>(b.data()));  // in place
      CHECK((b - x).norm() == 0.0);
    }
    const Eigen::MatrixXd b4 = Eigen::MatrixXd::Random(a.rows(), 4);
    Eigen::MatrixXd x4(a.rows(), 4);
    factor.solve4(b4.data(), x4.data());
    for (Eigen::Index r = 0; r < 4; ++r) {
      const Eigen::VectorXd expected = llt.solve(b4.col(r));
      CHECK((x4.col(r) - expected).norm() <= 1e-9 * expected.norm());
    }
  };
  // Random node graphs (elements of 1-5 nodes, then of 1-12, 3 x 3 blocks): diagonally
  // dominant, so positive definite; supernodes of 1..3 columns and wider than eight
  // (the solves' blocks of four and eight columns and every remainder).
  for (int round = 0; round < 12; ++round) {
    const std::size_t nodes = 2 + static_cast<std::size_t>(test::uniform(rng, 0, 120));
    std::vector<std::vector<std::size_t>> elements(nodes + static_cast<std::size_t>(test::uniform(rng, 0, 200)));
    for (auto& e : elements) {
      e.resize(static_cast<std::size_t>(test::uniform(rng, 1, round < 6 ? 5.99 : 12.99)));
      for (auto& v : e) v = static_cast<std::size_t>(test::uniform(rng, 0, static_cast<double>(nodes) - 1e-9));
    }
    for (std::size_t i = 0; i < nodes; ++i) elements[i] = {i};  // every diagonal block present
    std::vector<std::span<const std::size_t>> spans(elements.begin(), elements.end());
    BlockAssembly assembly(nodes, spans);
    for (const auto& e : elements) {
      for (std::size_t r : e) {
        for (std::size_t c : e) {
          if (r <= c) assembly.add(r, c, r == c ? Mat3(Mat3::Identity() * 60.0) : Mat3(Mat3::Constant(0.5)));
        }
      }
    }
    check(assembly.upper(), test::uniform(rng, 0.0, 1.0));
  }
  // K of a design (positive semi-definite: six rigid motions), shifted as the modes shift it.
  const Design design = load_design(std::filesystem::path(test::presets) / "grid-3x3.json");
  for (PanelModel panels : {PanelModel::n4b5, PanelModel::n5b8}) {
    const BarHingeModel model = model_at_04(design, panels);
    const Eigen::SparseMatrix<double> k = model.stiffness();
    check(k, 1e-6 * k.diagonal().maxCoeff());
    const Eigen::SparseMatrix<double> upper = model.stiffness_upper();
    CHECK(Eigen::SparseMatrix<double>(k - Eigen::SparseMatrix<double>(k.transpose())).norm() == 0.0);
    CHECK(Eigen::SparseMatrix<double>(Eigen::SparseMatrix<double>(k.triangularView<Eigen::Upper>()) - upper).norm() == 0.0);
    check(upper, 1e-6 * k.diagonal().maxCoeff());
    // Not positive definite: a clear internal error, nothing printed.
    CHECK_THROWS_AS(NodeCholesky(k, -1.0), Error);
  }
}

TEST_CASE("the Cholesky factor's ordering: nested dissection where it has fewer entries than AMD (a 3D lattice), AMD where it has (a chain)",
          "[mechanics]") {
  // Nodes of three rows, coupled to their lattice neighbours (3 x 3 blocks); diagonally
  // dominant. CHOLMOD's own choice kept AMD on such node graphs (docs/performance.md).
  const auto lattice = [](int nx, int ny, int nz) {
    const int nodes = nx * ny * nz;
    std::vector<std::vector<std::size_t>> elements;
    const auto id = [&](int x, int y, int z) { return static_cast<std::size_t>((z * ny + y) * nx + x); };
    for (int z = 0; z < nz; ++z) {
      for (int y = 0; y < ny; ++y) {
        for (int x = 0; x < nx; ++x) {
          elements.push_back({id(x, y, z)});
          if (x + 1 < nx) elements.push_back({id(x, y, z), id(x + 1, y, z)});
          if (y + 1 < ny) elements.push_back({id(x, y, z), id(x, y + 1, z)});
          if (z + 1 < nz) elements.push_back({id(x, y, z), id(x, y, z + 1)});
        }
      }
    }
    std::vector<std::span<const std::size_t>> spans(elements.begin(), elements.end());
    BlockAssembly assembly(static_cast<std::size_t>(nodes), spans);
    for (const auto& e : elements) {
      for (std::size_t r : e) {
        for (std::size_t c : e) {
          if (r <= c) assembly.add(r, c, r == c ? Mat3(Mat3::Identity() * 40.0) : Mat3(Mat3::Constant(0.5)));
        }
      }
    }
    return assembly.upper();
  };
  const auto amd_entries = [](const Eigen::SparseMatrix<double>& a) {
    const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::AMDOrdering<int>> llt(a);
    REQUIRE(llt.info() == Eigen::Success);
    return static_cast<double>(llt.matrixL().nestedExpression().nonZeros());
  };
  const auto solves = [](const Eigen::SparseMatrix<double>& a, const NodeCholesky& factor) {
    const Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
    Eigen::VectorXd x(a.rows());
    factor.solve(b.data(), x.data());
    CHECK((a.selfadjointView<Eigen::Upper>() * x - b).norm() <= 1e-12 * b.norm());
  };
  const Eigen::SparseMatrix<double> cube = lattice(12, 12, 12);
  const NodeCholesky cube_factor(cube);
  solves(cube, cube_factor);
  const double amd = amd_entries(cube);
  INFO("entries " << cube_factor.factor_entries() << ", AMD's " << amd);
  CHECK(cube_factor.factor_entries() < 0.9 * amd);
  const int length = 1200;
  const Eigen::SparseMatrix<double> chain = lattice(length, 1, 1);
  const NodeCholesky chain_factor(chain);
  solves(chain, chain_factor);
  CHECK(chain_factor.factor_entries() == 6.0 * length + 9.0 * (length - 1));  // no fill: AMD's
  CHECK(amd_entries(chain) == chain_factor.factor_entries());
}

TEST_CASE("charts: every glyph inside the page, the shared axis's label drawn where the last panel has its own axis",
          "[mechanics]") {
  // cairo writes text as glyphs placed at their baselines (<use ... x= y=>).
  const auto baselines = [](const std::string& svg) {
    std::vector<double> ys;
    const std::regex glyph(R"re(<use xlink:href="#glyph[0-9-]+" x="[-0-9.e]+" y="([-0-9.e]+)")re");
    for (std::sregex_iterator it(svg.begin(), svg.end(), glyph), end; it != end; ++it) ys.push_back(std::stod((*it)[1]));
    return ys;
  };
  const auto page_height = [](const std::string& svg) {
    std::smatch m;
    REQUIRE(std::regex_search(svg, m, std::regex(R"re(height="([0-9.]+)pt")re")));
    return std::stod(m[1]);
  };
  ChartSeries line{"a line", {0.0, 0.5, 1.0}, {1.0, 2.0, 1.5}, 0, false};
  ChartPanel shared{"on the chart's axis", "y", {}, "", false, {line}, {}, {}, {}, {}};
  ChartPanel own{"on an axis of its own", "y", std::pair{10.0, 20.0}, "stroke", false, {line}, {}, {}, {}, {}};
  own.series[0].x = {10.0, 15.0, 20.0};
  for (const std::vector<ChartPanel>& panels : {std::vector<ChartPanel>{shared}, std::vector<ChartPanel>{shared, shared},
                                                std::vector<ChartPanel>{shared, shared, own}}) {
    Chart chart{"title", "subtitle", "motion parameter t", 0.0, 1.0, panels};
    const std::string svg = chart_svg(chart);
    const std::vector<double> ys = baselines(svg);
    REQUIRE_FALSE(ys.empty());
    // A 13-point label's descenders reach about 3 points below its baseline.
    CHECK(*std::max_element(ys.begin(), ys.end()) <= page_height(svg) - 8.0);
    // The chart's x label is drawn once (a glyph a character, spaces too), whichever panel carries it.
    chart.x_label.clear();
    CHECK(baselines(chart_svg(chart)).size() + std::string("motion parameter t").size() == ys.size());
  }
}

TEST_CASE("huge pages: a virtio balloon that reports free pages is recognized, nothing else is", "[mechanics]") {
  const test::TempDir dir("virtio");
  const auto device = [&](const std::string& name, const std::string& id, const std::string& features) {
    std::filesystem::create_directories(dir.path / name);
    std::ofstream(dir.path / name / "device") << id << "\n";
    std::ofstream(dir.path / name / "features") << features << "\n";
  };
  CHECK_FALSE(reports_free_pages(dir.path / "absent"));  // not a virtio guest
  CHECK_FALSE(reports_free_pages(dir.path));            // no devices
  // A network device with bit 5 set, a balloon without it (statistics and deflate on OOM only).
  device("virtio1", "0x0001", "11000101101110110000000000000100");
  device("virtio0", "0x0005", "01100001000000000000000000000000");
  CHECK_FALSE(reports_free_pages(dir.path));
  // This VM's balloon: statistics, deflate on OOM, free page reporting (bit 5).
  device("virtio0", "0x0005", "01100101000000000000000000000000");
  CHECK(reports_free_pages(dir.path));
  device("virtio0", "0x0005", "0110");  // a features string too short to say
  CHECK_FALSE(reports_free_pages(dir.path));
}

TEST_CASE("block Lanczos: the largest eigenpairs of (K + shift I)^-1 off the rigid motions, against a dense solve",
          "[mechanics]") {
  const Design design = load_design(std::filesystem::path(test::presets) / "grid-3x3.json");
  for (PanelModel panels : {PanelModel::n4b5, PanelModel::n5b8}) {
    const BarHingeModel model = model_at_04(design, panels);
    const Eigen::SparseMatrix<double> k = model.stiffness();
    const Eigen::MatrixXd rigid = rigid_motion_basis(model.positions());
    const double shift = 1e-10 * k.diagonal().maxCoeff();
    const NodeCholesky factor(k, shift);
    const auto project = [&](Eigen::MatrixXd& x) { x -= rigid * (rigid.transpose() * x); };
    const ApplyFour apply = [&](const Eigen::MatrixXd& in, Eigen::MatrixXd& out) {
      Eigen::MatrixXd x = in;
      project(x);
      out.resize(in.rows(), 4);
      factor.solve4(x.data(), out.data());
      project(out);
    };
    std::mt19937_64 rng(3608);
    Eigen::MatrixXd start(k.rows(), 4);
    for (Eigen::Index i = 0; i < start.size(); ++i) start.data()[i] = test::uniform(rng, -1, 1);
    project(start);
    for (Eigen::Index nev : {1, 6, 10}) {
      INFO(to_string(panels) << " nev " << nev << " rows " << k.rows());
      const std::optional<Eigen::MatrixXd> v = block_lanczos_largest(apply, start, nev, 1e-6, 200);
      REQUIRE(v.has_value());
      // The dense truth: K's eigenvalues off the rigid motions, ascending (the inverse's largest).
      const Eigen::HouseholderQR<Eigen::MatrixXd> qr(rigid);
      const Eigen::MatrixXd q = Eigen::MatrixXd(qr.householderQ()).rightCols(k.rows() - 6);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(q.transpose() * (Eigen::MatrixXd(k) * q));
      for (Eigen::Index i = 0; i < nev; ++i) {
        const Eigen::VectorXd x = v->col(i);
        CHECK(std::abs(x.norm() - 1.0) <= 1e-12);
        CHECK((rigid.transpose() * x).norm() <= 1e-9);
        const double lambda = x.dot(k * x);
        CHECK(std::abs(lambda - dense.eigenvalues()(i)) <= 1e-8 * dense.eigenvalues()(i));
      }
    }
    // A basis too small to converge: empty (the caller falls back to Spectra).
    CHECK_FALSE(block_lanczos_largest(apply, start, 6, 1e-14, 12).has_value());
  }
}

TEST_CASE("the modes of a 10^4-row model (block Lanczos) equal Spectra's single-vector Lanczos on the same factor",
          "[mechanics]") {
  const Design array = bench::mechanics_array(10, 11);  // 11,616 rows: the block method's side of the line
  StiffnessOptions options;
  options.panels = PanelModel::n5b8;
  const BarHingeModel model(array, array.assembly.evaluate(array.assembly.t_star()), options);
  const Eigen::SparseMatrix<double> k = model.stiffness();
  REQUIRE(k.rows() >= 10000);
  const Eigen::MatrixXd rigid = rigid_motion_basis(model.positions());
  const Eigenpairs pairs = smallest_eigenpairs(model.stiffness_upper(), rigid, 6);  // as analyze_modes calls it
  // Spectra on an operator of the test's own (the whole K): P (K + shift I)^-1 P with the same factor type.
  struct Operator {
    using Scalar = double;
    const Eigen::SparseMatrix<double>& k;
    const Eigen::MatrixXd& rigid;
    NodeCholesky factor;
    Eigen::Index rows() const { return k.rows(); }
    Eigen::Index cols() const { return k.cols(); }
    void set_shift(double) {}
    void perform_op(const double* in, double* out) const {
      Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(in, k.rows());
      x -= rigid * (rigid.transpose() * x);
      factor.solve(x.data(), out);
      Eigen::Map<Eigen::VectorXd> y(out, k.rows());
      y -= rigid * (rigid.transpose() * y);
    }
  };
  const double shift = 1e-10 * k.diagonal().maxCoeff();
  Operator op{k, rigid, NodeCholesky(k, shift)};
  Spectra::SymEigsShiftSolver<Operator> eigs(op, 6, 30, -shift);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 2000, 1e-10, Spectra::SortRule::SmallestAlge);
  REQUIRE(eigs.info() == Spectra::CompInfo::Successful);
  for (Eigen::Index i = 0; i < 6; ++i) {
    const Eigen::VectorXd v = eigs.eigenvectors().col(i).normalized();
    const double expected = v.dot(k * v);
    INFO("eigenvalue " << i);
    CHECK(std::abs(pairs.values(i) - expected) <= 1e-9 * expected);
    CHECK(std::abs(pairs.vectors.col(i).dot(v)) >= 1.0 - 1e-9);
  }
}

TEST_CASE("the mobility's SVD (LAPACK): A V = U S, V orthonormal and complete, rank-deficient and empty shapes", "[mechanics]") {
  std::mt19937_64 rng(37);
  for (const auto& [rows, cols, rank] : std::vector<std::array<int, 3>>{
           {0, 4, 0}, {5, 0, 0}, {1, 1, 1}, {7, 3, 3}, {3, 7, 3}, {40, 25, 18}, {25, 40, 25}, {60, 60, 51}}) {
    Eigen::MatrixXd left(rows, rank), right(rank, cols);
    for (Eigen::Index i = 0; i < left.size(); ++i) left.data()[i] = test::uniform(rng, -1, 1);
    for (Eigen::Index i = 0; i < right.size(); ++i) right.data()[i] = test::uniform(rng, -1, 1);
    const Eigen::MatrixXd a = left * right;
    const RightSingular svd = right_singular(a);
    INFO(rows << " x " << cols << " of rank " << rank);
    REQUIRE(svd.values.size() == std::min(rows, cols));
    REQUIRE(svd.vectors.rows() == cols);
    REQUIRE(svd.vectors.cols() == cols);
    if (cols == 0) continue;
    CHECK((svd.vectors.transpose() * svd.vectors - Eigen::MatrixXd::Identity(cols, cols)).norm() < 1e-12 * cols);
    const double scale = std::max(1.0, svd.values.size() > 0 ? svd.values(0) : 0.0);
    for (int k = 0; k < cols; ++k) {
      const double expected = k < svd.values.size() ? svd.values(k) : 0.0;
      if (k > 0 && k < svd.values.size()) CHECK(svd.values(k) <= svd.values(k - 1));
      CHECK(std::abs((a * svd.vectors.col(k)).norm() - expected) < 1e-12 * scale * cols);
      if (k >= rank) CHECK(expected < 1e-12 * scale * cols);  // the null space's basis
    }
  }
}

TEST_CASE("the exact motion's energy equals the bar-and-hinge energy of the same positions", "[mechanics]") {
  // Along the exact motion bars keep their lengths and bending hinges stay flat: the
  // model's whole energy (bars, bends, folds at rest at T0) is the fold energy.
  const Design design = load_design(std::filesystem::path(test::presets) / "parallelogram-tube.json");
  const double rest = design.assembly.t_at_fraction(0.3);
  const FoldEnergy fold(design, rest, StiffnessOptions{});
  const BarHingeModel& m = fold.model();
  std::vector<double> rest_angles;
  for (std::size_t h = 0; h < m.hinges().size(); ++h) rest_angles.push_back(m.angle(h, m.positions()));
  for (double f : {0.05, 0.5, 0.9}) {
    const double t = design.assembly.t_at_fraction(f);
    std::vector<double> angles;
    const double e = fold.energy(t, angles);
    Points x;
    m.node_positions(design.assembly.evaluate(t), x);
    double total = 0.0;
    for (const Bar& b : m.bars()) {
      const double stretch = (x[b.nodes[1]] - x[b.nodes[0]]).norm() - b.length;
      total += 0.5 * b.stiffness / b.length * stretch * stretch;
    }
    for (std::size_t h = 0; h < m.hinges().size(); ++h) {
      const Hinge& hinge = m.hinges()[h];
      const double d = continuous_angle(m.angle(h, x), rest_angles[h]) - rest_angles[h];
      total += 0.5 * hinge.stiffness * hinge.length * d * d;
    }
    CHECK(std::abs(total - e) <= 1e-12 * std::max(1.0, e));
    CHECK(e > 0.0);
  }
}

TEST_CASE("a bistable design: two minima and the barrier between them", "[mechanics]") {
  const Design design = load_design(std::filesystem::path(test::data) / "bistable.json");
  EnergyOptions o;
  o.rest_t = design.assembly.t_at_fraction(0.95);
  o.stiffness.panels = PanelModel::n4b5;
  const EnergyLandscape e = energy_landscape(design, o);
  REQUIRE(e.bistable());
  REQUIRE(e.equilibria.size() == 3);
  CHECK(e.equilibria[0].minimum);
  CHECK_FALSE(e.equilibria[1].minimum);
  CHECK(e.equilibria[2].rest);
  CHECK(*e.barrier == Approx(e.equilibria[1].energy));
  CHECK(*e.reverse_barrier == Approx(e.equilibria[1].energy - e.equilibria[0].energy));
  CHECK(*e.reverse_barrier > 0.0);
  // The same equilibria from more samples (to the refinement's accuracy).
  o.samples = 1001;
  const EnergyLandscape fine = energy_landscape(design, o);
  REQUIRE(fine.equilibria.size() == 3);
  for (std::size_t k = 0; k < 3; ++k) CHECK(std::abs(fine.equilibria[k].t - e.equilibria[k].t) <= 1e-10);
  // A monostable one: the shipped default.
  const Design open = load_design(std::filesystem::path(test::presets) / "default.json");
  o.rest_t = open.assembly.t_at_fraction(0.4);
  o.samples = 101;
  o.stiffness = {};
  const EnergyLandscape single = energy_landscape(open, o);
  CHECK_FALSE(single.bistable());
  CHECK(single.equilibria.size() == 1);
  CHECK_FALSE(single.barrier);
  // E >= 0, zero at the rest state, dE/dt none only at the limits.
  for (const EnergySample& s : single.samples) {
    CHECK(s.energy >= 0.0);
    CHECK(s.rate.has_value() == (s.t != open.assembly.flexion_interval().lower.t && s.t != open.assembly.flexion_interval().upper.t));
  }
}

TEST_CASE("the energy landscape's lengths and forces are the strain's of every member vertex, on every shipped preset", "[mechanics]") {
  // The landscape reads the strain from the corner nodes (each once, with the
  // weights of the member vertices at it) where every vertex is at a node:
  // against HomogenizedStrain::at from every vertex, and force = (dE/dt) / (dL/dt).
  std::size_t checked = 0, with_fewer_nodes = 0;
  auto strain_vertices = [](const Assembly& a) {
    std::size_t n = 0;
    for (std::size_t m = 0; m < a.member_count(); ++m) n += a.topology(m).vertex_count();
    return n;
  };
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    INFO(entry.path().filename().string());
    const Design design = load_design(entry.path());
    const Assembly& a = design.assembly;
    EnergyOptions o;
    o.rest_t = a.t_at_fraction(0.4);
    o.samples = 21;
    o.stiffness = default_stiffness(design);  // n5b8 unless a panel is not convex
    const EnergyLandscape e = energy_landscape(design, o);
    const HomogenizedStrain strain(a, o.axes);
    const std::array<double, 3> at_star = axis_extents(a.evaluate(a.t_star()).members, strain.axes());
    // The nodes' path on every shipped preset (coupled arrays: fewer nodes than member vertices).
    const std::optional<std::vector<std::uint32_t>> at_nodes = vertex_nodes(FoldEnergy(design, o.rest_t, o.stiffness), o.rest_t);
    REQUIRE(at_nodes);
    CHECK(at_nodes->size() == strain_vertices(a));
    with_fewer_nodes += a.member_count() > 1 && std::set<std::uint32_t>(at_nodes->begin(), at_nodes->end()).size() < at_nodes->size();
    const double span = a.flexion_interval().upper.t - a.flexion_interval().lower.t;
    for (const EnergySample& s : e.samples) {
      const HomogenizedStrain::State state = strain.at(s.t);
      for (int k = 0; k < 3; ++k) {
        REQUIRE(s.length[k].has_value() == state.stretch[k].has_value());
        if (!s.length[k]) continue;
        const double length = at_star[k] * *state.stretch[k];
        CHECK(std::abs(*s.length[k] - length) <= 1e-12 * length);
        if (!s.force[k]) continue;
        REQUIRE(s.rate);
        // dL/dt that the force divides by (near a pole the force itself is ill-conditioned), against the
        // length's scale over the interval.
        CHECK(std::abs(*s.rate / *s.force[k] - length * *state.rate[k]) <= 1e-10 * length / span);
        ++checked;
      }
    }
  }
  CHECK(checked > 200);
  CHECK(with_fewer_nodes >= 4);
}

TEST_CASE("the energy landscape at rest a hair inside a flexion limit: the rest state its minimum, no step past the limit", "[mechanics]") {
  // t* of this fixture is 1.1e-8 above t_lambda, less than the step (1e-6 of the
  // interval) the equilibria take beside a sample: taken whole, it left the interval.
  const Design design = load_design(std::filesystem::path(test::data) / "partly-buildable.json");
  const double t_lambda = design.assembly.flexion_interval().lower.t;
  REQUIRE(design.assembly.t_star() - t_lambda > 0.0);
  REQUIRE(design.assembly.t_star() - t_lambda < 1e-6 * (design.assembly.flexion_interval().upper.t - t_lambda));
  EnergyOptions o;
  o.rest_t = design.assembly.t_star();
  o.samples = 51;
  o.stiffness.panels = PanelModel::n4b5;
  const EnergyLandscape e = energy_landscape(design, o);
  REQUIRE(e.equilibria.size() >= 1);
  CHECK(e.equilibria.front().rest);
  CHECK(e.equilibria.front().minimum);
  CHECK(e.equilibria.front().energy == Approx(0.0).margin(1e-20));
}

TEST_CASE("the energy landscape on two threads (parts taken afresh and joined) equals one walk, bit for bit, forces too", "[mechanics]") {
  // The rest state near either end (one side nearly all the samples: the thread
  // done with the shorter side takes the far half of the longer one, starting
  // afresh, and either thread then takes the other's far half while 16 samples or
  // more are left; the parts are joined afterwards, or walked again where a fold
  // turned past half a turn), on every shipped preset and the bistable design.
  std::vector<std::filesystem::path> files{std::filesystem::path(test::data) / "bistable.json"};
#ifdef PHEDRA_SANITIZE_BUILD
  files.push_back(std::filesystem::path(test::presets) / "grid-3x3.json");  // the code paths (30 s for all there)
#else
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "preset.schema.json") files.push_back(entry.path());
  }
#endif
  for (const auto& file : files) {
    const Design design = load_design(file);
    for (const double rest : {0.03, 0.97}) {
      EnergyOptions o = rest_at(design, rest);
      const std::size_t folds = FoldEnergy(design, o.rest_t, o.stiffness).model().fold_count();
      o.samples = std::max<std::size_t>(101, static_cast<std::size_t>(2e5 / static_cast<double>(folds)) + 2);
      const EnergyLandscape two = energy_landscape(design, o);
      o.two_threads = false;
      const EnergyLandscape one = energy_landscape(design, o);
      INFO(file.filename().string() << " at rest fraction " << rest << ", " << o.samples << " samples");
      REQUIRE(two.samples.size() == one.samples.size());
      for (std::size_t i = 0; i < one.samples.size(); ++i) {
        CHECK(two.samples[i].energy == one.samples[i].energy);
        CHECK(two.samples[i].rate == one.samples[i].rate);
        CHECK(two.samples[i].length == one.samples[i].length);
        CHECK(two.samples[i].force == one.samples[i].force);
      }
      REQUIRE(two.equilibria.size() == one.equilibria.size());
      for (std::size_t i = 0; i < one.equilibria.size(); ++i) CHECK(two.equilibria[i].t == one.equilibria[i].t);
    }
  }
}

TEST_CASE("the energy landscape's coarse samples are its fine samples, bit for bit (four at a time, and alone where a fold turns fast)", "[mechanics]") {
  // Samples 5, 9 and 17 are every 16th, 8th and 4th of 65, the rest state near
  // either end: the coarse walks take steps where folds turn past half a radian,
  // so a sample of four falls back to one at a time with halved steps (eight
  // times here); at every shared t the angles are the same whole turns from the
  // same raw angles, so E and dE/dt are equal.
  std::vector<std::filesystem::path> files{std::filesystem::path(test::data) / "bistable.json"};
  for (const char* name : {"default.json", "grid-3x3.json", "anti-parallelogram-tube.json", "tilted-axis.json"}) {
    files.push_back(std::filesystem::path(test::presets) / name);
  }
  for (const auto& file : files) {
    const Design design = load_design(file);
    for (const double rest : {0.03, 0.97}) {
      EnergyOptions o = rest_at(design, rest);
      o.samples = 65;
      const EnergyLandscape fine = energy_landscape(design, o);
      for (const std::size_t coarse_samples : {std::size_t{5}, std::size_t{9}, std::size_t{17}}) {
        o.samples = coarse_samples;
        const EnergyLandscape coarse = energy_landscape(design, o);
        INFO(file.filename().string() << ", rest at " << rest << ", " << coarse_samples << " samples against 65");
        for (const EnergySample& c : coarse.samples) {
          const auto f =
              std::find_if(fine.samples.begin(), fine.samples.end(), [&](const EnergySample& s) { return s.t == c.t; });
          REQUIRE(f != fine.samples.end());
          CHECK(c.energy == f->energy);
          CHECK(c.rate == f->rate);
          CHECK(c.length == f->length);
          CHECK(c.force == f->force);
        }
      }
    }
  }
}

TEST_CASE("phedra mechanics: JSON fields, files, and every bad option a clear error with exit 2", "[mechanics][cli]") {
  using test::phedra_cli;
  const std::string preset = test::presets + "/parallelogram-tube.json";
  test::TempDir dir("mechanics");
  const test::Run run = phedra_cli({"mechanics", preset, "--fraction", "0.4", "--json"});
  REQUIRE(run.code == 0);
  const nlohmann::json j = nlohmann::json::parse(run.out);
  for (const char* key : {"t", "panels", "nodes", "bars", "hinges", "rigid_body_modes", "eigenvalues", "motion_alignment",
                          "gap", "motion_stiffness", "mobility"}) {
    CHECK(j.contains(key));
  }
  CHECK(j["rigid_body_modes"] == 6);
  CHECK(j["eigenvalues"].size() == 6);
  CHECK(j["mobility"]["internal_mechanisms"] == 1);
  const test::Run files = phedra_cli({"mechanics", preset, "--over-interval", "12", "-o", dir / "m.csv", "-o", dir / "m.svg",
                                      "-o", dir / "m.png", "-o", dir / "m.json"});
  REQUIRE(files.code == 0);
  CHECK(std::filesystem::file_size(dir / "m.png") > 10000);
  CHECK(test::read_json(dir / "m.json")["over_interval"]["configurations"].size() == 12);
  const test::Run energy = phedra_cli({"mechanics", preset, "--energy", "--rest-fraction", "0.5", "--samples", "21", "-o",
                                       dir / "e.csv", "-o", dir / "e.json", "-o", dir / "modes.glb"});
  REQUIRE(energy.code == 0);
  const nlohmann::json e = test::read_json(dir / "e.json");
  CHECK(e["energy"].size() == 21);  // the rest state is a sample already
  CHECK(e["equilibria"][0]["kind"] == "minimum");
  CHECK(std::filesystem::file_size(dir / "modes.glb") > 1000);
  struct Bad {
    std::vector<std::string> args;
    const char* says;
  };
  const std::vector<Bad> bad = {
      {{"--bar", "-1"}, "--bar"},
      {{"--fold", "0"}, "--fold"},
      {{"--bend", "nan"}, "--bend"},
      {{"--panels", "n6b9"}, "--panels"},
      {{"--modes", "0"}, "--modes"},
      {{"--modes", "100000"}, "--modes: must be a whole number from 1 to 1000 (got 100000)"},
      {{"--energy"}, "--rest-t"},
      {{"--energy", "--rest-t", "99"}, "outside the flexion interval"},
      {{"--energy", "--rest-fraction", "1.5"}, "fraction"},
      {{"--rest-t", "1"}, "only with --energy"},
      {{"--t", "99"}, "outside"},
      {{"--material", "1000"}, "--material"},
      {{"--material", "1000,0.3"}, "--thickness"},
      {{"--material", "1000,0.6", "--thickness", "0.1"}, "Poisson"},
      {{"--material", "1000,0.3", "--thickness", "0.1", "--panels", "n4b5"}, "n5b8 panels only"},
      {{"--thickness", "0.1"}, "only with --material"},
      {{"--over-interval", "1"}, "--over-interval: must be a whole number from 2 to 100000 (got 1)"},
      {{"-o", "x.csv"}, "--over-interval or --energy"},
      {{"-o", "x.stl"}, "unknown format"},
  };
  for (const Bad& b : bad) {
    std::vector<std::string> args = {"mechanics", preset};
    args.insert(args.end(), b.args.begin(), b.args.end());
    const test::Run r = phedra_cli(args);
    INFO(args.back());
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Matchers::Contains(b.says));
  }
  CHECK_FALSE(std::filesystem::exists("x.csv"));
}
