#pragma once
// The figures of `phedra bench` (issue 5, docs/performance.md): each measured in
// this process (one core) next to its target and the machine's memory-bandwidth
// reference.

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace phedra::bench {

struct Figure {
  std::string id;           ///< stable key, e.g. "evaluate.ratio_to_write_1e6"
  std::string description;  ///< what was measured, on which case
  double value = 0.0;
  std::string unit;
  std::optional<double> target;  ///< an upper bound, when the figure has one
  bool met() const { return !target || value <= *target; }
};

struct BenchOptions {
  /// Smaller cases (up to 10^5 vertices, 10^3 profiles, 3 x 3 cells, 10^3 panels):
  /// a smoke run whose figures are not comparable with the targets.
  bool quick = false;
  /// Largest evaluate case (10^7 by default).
  std::size_t max_vertices = 10'000'000;
  /// Only the groups named (memory, evaluate, accuracy, interval, closure, gltf,
  /// repair, optimize, mechanics); empty: all.
  std::vector<std::string> only;
};

/// The group names BenchOptions::only takes.
const std::vector<std::string>& bench_groups();

struct BenchReport {
  bool quick = false;
  std::string machine;  ///< CPU model and core count
  std::vector<Figure> figures;
  bool all_met() const;
  nlohmann::json to_json() const;
};

/// Runs every benchmark; `progress` (optional) gets the name of each before it runs.
BenchReport run_benchmarks(const BenchOptions& options, const std::function<void(const std::string&)>& progress = {});

std::ostream& operator<<(std::ostream& out, const BenchReport& report);

}  // namespace phedra::bench
