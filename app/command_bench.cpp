// phedra bench [--json] [--quick] [--max-vertices N] [--only GROUP]... [-o FILE]

#include "commands.h"
#include "number_checks.h"
#include "support.h"

#include "phedra/bench_figures.h"

#include <iostream>
#include <memory>
#include <sstream>

namespace phedra::cli {
namespace {

struct BenchCommandOptions {
  bool json = false;
  bench::BenchOptions bench;
  std::string output;
};

}  // namespace

void add_bench_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<BenchCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "bench",
      "Measure the performance figures (docs/performance.md) on generated cases, each next to its target and the "
      "memory-bandwidth reference; one core (the energy landscape and large collision sweeps on two threads, as the "
      "commands run them), about a minute. Exit code 1 when a target is missed");
  sub->add_flag("--json", options->json, "Print the figures as JSON");
  sub->add_flag("--quick", options->bench.quick,
                "Small cases only (a few seconds; the figures are not comparable with the targets, which are "
                "then not enforced)");
  sub->add_option("--max-vertices", options->bench.max_vertices, "Largest evaluate(t) case (default 10^7)")
      ->check(whole_number_between(1000, 100000000));
  sub->add_option("--only", options->bench.only,
                  "Only these groups of figures (repeatable): memory, evaluate, accuracy, interval, closure, gltf, "
                  "repair, optimize, mechanics")
      ->check(CLI::IsMember(bench::bench_groups()));
  sub->add_option("-o,--output", options->output, "Output file (default: standard output)");
  sub->callback([options, &context] {
    const bool show_progress = !options->json || !options->output.empty();
    const bench::BenchReport report = bench::run_benchmarks(options->bench, [&](const std::string& what) {
      if (show_progress) context.err << "bench: " << what << "\n";
    });
    std::ostringstream text;
    if (options->json) {
      text << report.to_json().dump(2) << "\n";
    } else {
      text << report;
    }
    emit(text.str(), options->output, "", context.out);
    if (!options->bench.quick && !report.all_met()) context.exit_code = 1;
  });
}

}  // namespace phedra::cli
