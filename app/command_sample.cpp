// phedra sample PRESET (--t T | --fraction F | --count N)... [-o FILE]

#include "commands.h"
#include "phedra/errors.h"
#include "phedra/sample_writer.h"
#include "support.h"

#include <memory>

namespace phedra::cli {
namespace {

struct SampleOptions {
  std::string preset;
  std::vector<double> t;
  std::vector<double> fraction;
  std::size_t count = 0;
  std::string output;
};

}  // namespace

void add_sample_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<SampleOptions>();
  CLI::App* sub = app.add_subcommand(
      "sample", "Vertex positions at chosen motion parameters t, as JSON {labels, faces, samples: [{t, vertices}]}");
  sub->add_option("preset", options->preset, "Preset file (JSON, docs/presets.md)")->required();
  CLI::Option* t_option = sub->add_option("--t", options->t, "A motion parameter t in [t_lambda, t_mu] (repeatable)")
                              ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  CLI::Option* f_option =
      sub->add_option("--fraction", options->fraction,
                      "A fraction F of the flexion interval: t = t_lambda + F (t_mu - t_lambda); 0 and 1 are "
                      "the limits (repeatable)")
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--count", options->count, "N configurations evenly spread over the interval, limits included")
      ->check(CLI::Range(2, 1000000));
  sub->add_option("-o,--output", options->output, "Output file (default: standard output)");
  sub->callback([options, sub, t_option, f_option, &context] {
    const PHedron p = load_phedron(context, options->preset);
    // t values in the order given on the command line.
    std::vector<double> ts;
    std::size_t next_t = 0, next_f = 0;
    for (const CLI::Option* option : sub->parse_order()) {
      if (option == t_option) ts.push_back(options->t.at(next_t++));
      if (option == f_option) ts.push_back(p.t_at_fraction(options->fraction.at(next_f++)));
    }
    for (std::size_t k = 0; k < options->count; ++k) {
      ts.push_back(p.t_at_fraction(static_cast<double>(k) / static_cast<double>(options->count - 1)));
    }
    if (ts.empty()) throw InvalidInputError("", "give at least one --t, --fraction or --count");
    emit(sample_json(p, ts), options->output, options->preset, context.out);
  });
}

}  // namespace phedra::cli
