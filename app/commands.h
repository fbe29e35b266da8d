#pragma once
// The subcommands. Each registers its options on `app` and runs from its callback;
// errors are thrown (phedra::Error) and turned into messages and exit codes by run().

#include <CLI/CLI.hpp>

#include <iosfwd>

namespace phedra::cli {

/// Where commands write and the exit code a command sets (check: 1 on failure).
struct Context {
  std::ostream& out;
  std::ostream& err;
  int exit_code = 0;
  std::string preset;  ///< the preset being processed, for error messages
};

void add_info_command(CLI::App& app, Context& context);
void add_sample_command(CLI::App& app, Context& context);
void add_check_command(CLI::App& app, Context& context);
void add_intersections_command(CLI::App& app, Context& context);
void add_metrics_command(CLI::App& app, Context& context);
void add_outlines_command(CLI::App& app, Context& context);
void add_develop_command(CLI::App& app, Context& context);
void add_generate_command(CLI::App& app, Context& context);
void add_view_command(CLI::App& app, Context& context);
void add_bench_command(CLI::App& app, Context& context);
void add_repair_command(CLI::App& app, Context& context);
void add_optimize_command(CLI::App& app, Context& context);
void add_mechanics_command(CLI::App& app, Context& context);

}  // namespace phedra::cli
