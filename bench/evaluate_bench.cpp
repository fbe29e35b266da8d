// Baseline benchmarks for issue 5: evaluate(t) of an open P-hedron against the
// time to write the same vertex buffer (24 bytes a vertex), and the flexion
// interval search of long chains. Build: cmake -DPHEDRA_BUILD_BENCH=ON; run
// build-bench/bench/phedra_bench.

#include "phedra/phedron.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>

namespace {

/// An axial screw-symmetric P-hedron with about `vertices` vertices (m + 1 rows of n + 2).
phedra::ControlPolylines screw(std::size_t strips, std::size_t n) {
  phedra::ControlPolylines in;
  for (std::size_t i = 0; i <= strips; ++i) {
    const double a = 0.22 * static_cast<double>(i);
    in.trajectory.push_back(phedra::Vec3(3 * std::cos(a), 3 * std::sin(a), 0.35 * static_cast<double>(i)));
    in.directions.push_back(phedra::Vec3(std::cos(a), std::sin(a), 0));
  }
  for (std::size_t j = 0; j <= n; ++j) in.apex_heights.push_back(j % 2 ? 1.0 + 0.1 * j : -1.5 - 0.1 * j);
  in.signs.assign(n - 1, phedra::Sign::plus);
  return in;
}

void evaluate(benchmark::State& state) {
  const std::size_t n = 98;  // 100 columns with the boundary
  const std::size_t strips = static_cast<std::size_t>(state.range(0)) / (n + 2) - 1;
  const phedra::PHedron p(screw(strips, n));
  phedra::Points out(p.vertex_count());
  const double t = p.t_at_fraction(0.3);
  for (auto _ : state) {
    p.evaluate(t, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ns_per_vertex"] = benchmark::Counter(
      static_cast<double>(p.vertex_count()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(p.vertex_count() * 24));
}

void write_buffer(benchmark::State& state) {
  phedra::Points out(static_cast<std::size_t>(state.range(0)));
  double x = 0;
  for (auto _ : state) {
    x += 1.0;
    for (phedra::Vec3& v : out) v = phedra::Vec3(x, x, x);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ns_per_vertex"] = benchmark::Counter(
      static_cast<double>(out.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * state.range(0) * 24);
}

void flexion_interval(benchmark::State& state) {
  const phedra::ControlPolylines in = screw(static_cast<std::size_t>(state.range(0)), 4);
  for (auto _ : state) {
    const phedra::PHedron p(in);
    benchmark::DoNotOptimize(p.flexion_interval().upper.t);
  }
}

}  // namespace

BENCHMARK(evaluate)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(write_buffer)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(flexion_interval)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
