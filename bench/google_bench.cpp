// Google Benchmark versions of the figures of `phedra bench` (docs/performance.md),
// for profiling and for comparing builds:
//   build/bin/phedra_google_bench [--benchmark_filter=evaluate]
// evaluate(t) against writing the same vertex buffer at 10^3..10^7 vertices,
// the flexion interval of 10^4 profiles, the check of a 10 x 10 array and the
// glTF export of 10^4 panels.

#include "phedra/assembly_check.h"
#include "phedra/bench_cases.h"
#include "phedra/gltf_export.h"
#include "phedra/phedron.h"
#include "phedra/design_preset.h"
#include "phedra/self_intersection.h"
#include "phedra/keep_buildable.h"
#include "phedra/assembly_mesh.h"
#include "phedra/energy_landscape.h"
#include "phedra/stiffness_modes.h"

#include "../mechanics/src/node_cholesky.h"  // internal to mechanics/: its factorization and solve apart

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>

namespace {

using namespace phedra;

void per_vertex(benchmark::State& state, std::size_t vertices) {
  state.counters["ns_per_vertex"] = benchmark::Counter(static_cast<double>(vertices),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(vertices * 24));
}

void evaluate(benchmark::State& state) {
  const PHedron p(bench::open_input_with_vertices(static_cast<std::size_t>(state.range(0))));
  Points out(p.vertex_count());
  const double t = p.t_at_fraction(0.3);
  for (auto _ : state) {
    p.evaluate(t, out);
    benchmark::DoNotOptimize(out.data());
  }
  per_vertex(state, p.vertex_count());
}

/// The keep-buildable drag's check at t* on the designer bench's helix (strips = profiles - 1).
void collision_at_t_star(benchmark::State& state) {
  const Design design = design_from_json(bench::designer_helix_preset(static_cast<std::size_t>(state.range(0))));
  for (auto _ : state) benchmark::DoNotOptimize(self_intersection_at_t_star(design));
  state.counters["panels"] = static_cast<double>(panel_mesh(design).faces.size());
}

/// The parts of a keep-buildable drag step on the browser designer bench's model
/// of 10^4 vertices: the design built from its preset (0), its panel mesh (1), a
/// whole KeepBuildableDrag step of trajectory point 1 (2, 1e-3 up and down as
/// bench/designer.mjs moves it), as the designer's Designer.keep runs it.
void keep_step(benchmark::State& state) {
  nlohmann::json preset = bench::designer_grid_helix_preset(10000);
  const nlohmann::json start = preset["trajectory"][1];
  KeepBuildableDrag drag;
  int k = 0;
  for (auto _ : state) {
    const nlohmann::json previous = preset["trajectory"][1];
    preset["trajectory"][1] = {start[0].get<double>(), start[1].get<double>(), start[2].get<double>() + 1e-3 * std::sin(++k)};
    if (state.range(0) == 0) {
      benchmark::DoNotOptimize(design_from_json(preset).assembly.model_size());
    } else if (state.range(0) == 1) {
      static const Design design = design_from_json(preset);
      benchmark::DoNotOptimize(panel_mesh(design).faces.size());
    } else {
      ProjectionOptions options;
      options.max_seconds = 1.0;
      const std::optional<Projection> p = drag.step(preset, "/trajectory/1", previous, options);
      if (!p || p->how != "already") state.SkipWithError("the step did not stay buildable");
      benchmark::DoNotOptimize(p);
    }
  }
}

void write_buffer(benchmark::State& state) {
  Points out(static_cast<std::size_t>(state.range(0)));
  double x = 0;
  for (auto _ : state) {
    x += 1.0;
    for (Vec3& v : out) v = Vec3(x, x, x);
    benchmark::DoNotOptimize(out.data());
  }
  per_vertex(state, out.size());
}

void flexion_interval(benchmark::State& state) {
  const PHedron p(bench::general_open_input(static_cast<std::size_t>(state.range(0)), 4));
  for (auto _ : state) benchmark::DoNotOptimize(p.search_flexion_interval());
}

void construction(benchmark::State& state) {
  const ControlPolylines in = bench::general_open_input(static_cast<std::size_t>(state.range(0)), 4);
  for (auto _ : state) {
    const PHedron p(in);
    benchmark::DoNotOptimize(p.flexion_interval().upper.t);
  }
}

void array_check(benchmark::State& state) {
  const Design design = bench::parallelogram_array(10, 100);
  CheckOptions options;
  options.samples = 1000;
  options.shape = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(check_assembly(design.assembly, options).passed());
}

void gltf_export(benchmark::State& state) {
  const Design design = bench::open_design_with_panels(10000);
  GltfOptions options;
  options.keyframes.relative_tolerance = 1e9;
  options.keyframes.initial = options.keyframes.maximum = 200;
  for (auto _ : state) benchmark::DoNotOptimize(gltf_bytes(design, options).size());
}

}  // namespace

/// The energy landscape's parts on the mechanics bench's 10 x 10 array (`phedra
/// bench` mechanics.energy_1000_s): one sample (0: the corner nodes' positions and rates, 1: the
/// whole evaluation of E and dE/dt), the landscape of 1000 samples (2; 3:
/// on one thread), its set-up before the walk (4: the fold model at the rest
/// state), and four samples' corner nodes together (5: FoldEnergy::load_lanes, the walk's).
void energy(benchmark::State& state) {
  const Design array = bench::mechanics_array(10, 45);
  const double rest = array.assembly.t_star();
  const FoldEnergy fold(array, rest, StiffnessOptions{});
  FoldEnergy::Scratch scratch;
  std::vector<double> angles;
  const double t = array.assembly.t_at_fraction(0.4);
  const std::array<double, FoldEnergy::lanes> lane_ts{t, array.assembly.t_at_fraction(0.401),
                                                      array.assembly.t_at_fraction(0.402),
                                                      array.assembly.t_at_fraction(0.403)};
  EnergyOptions options;
  options.rest_t = rest;
  options.samples = 1000;
  options.two_threads = state.range(0) != 3;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      fold.nodes_at(t, scratch);
      benchmark::DoNotOptimize(scratch.x.data());
    } else if (state.range(0) == 1) {
      benchmark::DoNotOptimize(fold.evaluate(t, fold.rest_angles(), angles, scratch));
    } else if (state.range(0) == 5) {
      benchmark::DoNotOptimize(fold.load_lanes(lane_ts.data(), scratch));
    } else if (state.range(0) == 4) {
      benchmark::DoNotOptimize(FoldEnergy(array, rest, StiffnessOptions{}).rest_angles().data());
    } else {
      benchmark::DoNotOptimize(energy_landscape(array, options).folds);
    }
  }
  state.counters["folds"] = static_cast<double>(fold.model().fold_count());
}

/// The modes' parts on the same array (`phedra bench` mechanics.modes_array_s, n5b8):
/// 0 the whole figure (the model, K, the largest eigenvalue, 6 eigenpairs, the
/// alignment), 1 the Cholesky factor of K + delta I (ordering, analysis,
/// factorization), 2 one solve with it, 3 one solve of four right-hand sides,
/// 4 K's upper triangle (the assembly), 5 K's largest eigenvalue.
void modes(benchmark::State& state) {
  const Design array = bench::mechanics_array(10, 45);
  const double t = array.assembly.t_star();
  AssemblyConfiguration c;
  std::vector<Points> rates;
  array.assembly.evaluate_rate(t, c, rates);
  StiffnessOptions options;
  options.panels = PanelModel::n5b8;
  const BarHingeModel model(array, c, options);
  Points v;
  model.node_rates(rates, v);
  const Eigen::SparseMatrix<double> k = model.stiffness_upper();  // analyze_modes's
  const double shift = 1e-10 * k.diagonal().maxCoeff();  // analyze_modes's
  const std::unique_ptr<NodeCholesky> factor = state.range(0) == 2 || state.range(0) == 3 ? std::make_unique<NodeCholesky>(k, shift) : nullptr;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(k.rows());
  Eigen::MatrixXd x4 = Eigen::MatrixXd::Ones(k.rows(), 4);
  for (auto _ : state) {
    if (state.range(0) == 4) {
      benchmark::DoNotOptimize(model.stiffness_upper().nonZeros());
    } else if (state.range(0) == 5) {
      benchmark::DoNotOptimize(largest_eigenvalue(k));
    } else if (state.range(0) == 0) {
      const BarHingeModel m(array, c, options);
      benchmark::DoNotOptimize(analyze_modes(m, flatten(v), 6).eigenvalues.data());
    } else if (state.range(0) == 1) {
      benchmark::DoNotOptimize(NodeCholesky(k, shift));
    } else if (state.range(0) == 2) {
      factor->solve(x.data(), x.data());
      benchmark::DoNotOptimize(x.data());
    } else {
      factor->solve4(x4.data(), x4.data());
      benchmark::DoNotOptimize(x4.data());
    }
  }
}

BENCHMARK(evaluate)->RangeMultiplier(10)->Range(1000, 10000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(write_buffer)->RangeMultiplier(10)->Range(1000, 10000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(flexion_interval)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(construction)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(array_check)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);  // 0: --closure-only
BENCHMARK(gltf_export)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(collision_at_t_star)->Arg(111)->Arg(1111)->Unit(benchmark::kMillisecond);
BENCHMARK(keep_step)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(modes)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(energy)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
