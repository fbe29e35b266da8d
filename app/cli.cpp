#include "cli.h"

#include "commands.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <ostream>

namespace phedra::cli {

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  Context context{out, err, 0, {}};
  CLI::App app{"phedra: design and animate P-hedra, rigid-foldable planar-quad surfaces given by three "
               "control polylines (trajectory, directions, apexes)",
               "phedra"};
  app.set_version_flag("--version", std::string("phedra ") + PHEDRA_VERSION);
  app.require_subcommand(1);
  app.footer("Exit codes: 0 ok, 1 a check failed, 2 bad input, 3 file error, 4 internal error.\n"
             "Presets: docs/presets.md. Run `phedra COMMAND --help` for a command's options.");
  add_info_command(app, context);
  add_sample_command(app, context);
  add_check_command(app, context);
  add_repair_command(app, context);
  add_optimize_command(app, context);
  add_intersections_command(app, context);
  add_metrics_command(app, context);
  add_mechanics_command(app, context);
  add_outlines_command(app, context);
  add_develop_command(app, context);
  add_generate_command(app, context);
  add_view_command(app, context);
  add_bench_command(app, context);
  // Numbers meant for people: 6 significant digits unless asked (files keep full precision).
  set_full_precision(false);
  const std::string precision_help = "Print numbers with full (round-trip) precision instead of 6 significant digits "
                                     "(files and JSON always have full precision)";
  for (CLI::App* command : app.get_subcommands({})) {
    command->add_flag_callback("--full-precision", [] { set_full_precision(true); }, precision_help)->trigger_on_parse();
  }

  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp& e) {
    app.exit(e, out, err);
    return 0;
  } catch (const CLI::CallForAllHelp& e) {
    app.exit(e, out, err);
    return 0;
  } catch (const CLI::CallForVersion& e) {
    app.exit(e, out, err);
    return 0;
  } catch (const CLI::ParseError& e) {
    // The help of the command being parsed, when there is one.
    std::string command;
    for (const CLI::App* sub : app.get_subcommands()) command = sub->get_name() + " ";
    err << "phedra: error: " << e.what() << "\n";
    err << "Run `phedra " << command << "--help` for usage.\n";
    return static_cast<int>(ExitCode::bad_input);
  } catch (const InvalidInputError& e) {
    err << "phedra: error: " << (context.preset.empty() ? "" : context.preset + ": ") << e.what() << "\n";
    return static_cast<int>(e.exit_code());
  } catch (const Error& e) {
    err << "phedra: error: " << e.what() << "\n";
    return static_cast<int>(e.exit_code());
  } catch (const std::bad_alloc&) {
    err << "phedra: error: out of memory\n";
    return static_cast<int>(ExitCode::internal);
  } catch (const std::exception& e) {
    err << "phedra: internal error: " << e.what() << "\n";
    return static_cast<int>(ExitCode::internal);
  }
  return context.exit_code;
}

}  // namespace phedra::cli
