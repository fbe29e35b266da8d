// phedra develop PATTERN [--direction up|down] [--fold SIGNS] [--fraction F] [-o FILE]... [--json]

#include "commands.h"
#include "number_checks.h"
#include "phedra/crease_pattern.h"
#include "phedra/developed_pattern.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/preset.h"
#include "support.h"
#include "buildability_warning.h"
#include "phedra/developed_preset.h"
#include "phedra/files.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct DevelopOptions {
  std::string pattern;
  std::string direction;  ///< "", "up", "down"
  std::string fold;
  double fraction = 0.5;
  std::vector<std::string> outputs;
  bool json = false;
  double scale = 0.0;
  bool scale_given = false;
};

std::vector<int> fold_choices(const std::string& text, std::size_t strips) {
  if (text.empty()) return std::vector<int>(strips, 1);
  if (text.size() != strips) {
    throw InvalidInputError("--fold", "expected " + std::to_string(strips) + " signs (one per strip), got " +
                                          std::to_string(text.size()));
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '+' && text[i] != '-') {
      throw InvalidInputError("--fold", "character " + std::to_string(i) + " is '" + text.substr(i, 1) + "', expected + or -");
    }
    out.push_back(text[i] == '+' ? 1 : -1);
  }
  return out;
}

nlohmann::json direction_json(const FlexDirection& f) {
  return {{"direction", f.direction > 0 ? "up" : "down"},
          {"folds", f.folds},
          {"reason", f.reason},
          {"expansion", f.expansion},
          {"strip_folds", f.strip_folds},
          {"reach", f.folds ? nlohmann::json(f.reach) : nlohmann::json(nullptr)},
          {"flat_at_reach", f.folds && f.flat_at_reach}};
}

/// The chosen strips turn a crease past the fully folded state before the
/// requested fraction: nothing is written (its sign would contradict its
/// assignment and its panels pass through each other); says which creases and
/// up to which fraction the motion is consistent.
void refuse_fold_through(Context& context, const DevelopedPattern& pattern, const std::vector<int>& fold,
                         const DevelopOptions& o, const CreasePattern& creases, double span) {
  auto consistent = [&](double fraction) {
    const double t = pattern.t_star() + fraction * span, t_near = pattern.t_star() + 1e-3 * fraction * span;
    try {
      return crease_pattern(pattern, fold, t_near, t).contradicted.empty();
    } catch (const Error&) {
      return false;
    }
  };
  double good = 0.0, bad = o.fraction;
  for (int step = 0; step < 40; ++step) {
    const double middle = 0.5 * (good + bad);
    (consistent(middle) ? good : bad) = middle;
  }
  std::string list;
  for (std::size_t k = 0; k < creases.contradicted.size(); ++k) {
    const std::size_t e = creases.contradicted[k];
    if (k == 6) {
      list += " (and " + std::to_string(creases.contradicted.size() - 6) + " more)";
      break;
    }
    list += (k ? ", " : "") + std::to_string(e) + " (" + std::string(1, creases.assignment[e]) + ", " +
            format_human(creases.fold_angle[e]) + " deg at fraction " + format_human(o.fraction) + ")";
  }
  const std::string choices = o.fold.empty() ? std::string(pattern.strips(), '+') : o.fold;
  context.err << "phedra: " << o.pattern << ": with strip choices " << choices << " crease"
              << (creases.contradicted.size() > 1 ? "s " : " ") << list
              << " turn past the fully folded state (+-180 deg) before fraction " << format_human(o.fraction)
              << " of the motion: their panels pass through each other and their fold angles would contradict their "
                 "mountain/valley assignment. Nothing written. The motion is consistent up to fraction "
              << format_human(good) << " (--fraction " << format_human(std::floor(good * 1000.0) / 1000.0)
              << "); other --fold choices may fold further.\n";
  context.exit_code = static_cast<int>(ExitCode::check_failed);
}

}  // namespace

void add_develop_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<DevelopOptions>();
  CLI::App* sub = app.add_subcommand(
      "develop",
      "A P-hedron given in its developed (flat) state (docs/presets.md, Developed patterns): decide with the "
      "non-expansion criterion whether and which way it folds, write its crease pattern with mountain/valley "
      "assignment (SVG, FOLD) and the folded P-hedron as a preset for every other command; exit 1 when no real "
      "flex exists");
  sub->add_option("PATTERN", o->pattern, "Developed pattern file (JSON)")->required();
  sub->add_option("--direction", o->direction, "up (t increasing) or down; default: the one that folds")
      ->check(CLI::IsMember({"up", "down"}));
  sub->add_option("--fold", o->fold,
                  "Fold choice per strip, m characters + or - (default all +): each strip turns its profile plane one "
                  "way or the other; the choices fix the mountain/valley assignment");
  sub->add_option("--fraction", o->fraction,
                  "The folded state written (fold angles, .json preset): this fraction of the way from flat to the end "
                  "of the motion, in (0, 1)")
      ->check(number_between(1e-9, 1.0 - 1e-9))
      ->capture_default_str();
  sub->add_option("-o,--output", o->outputs,
                  "Write .svg or .pdf (the crease pattern to scale, with title, legend and scale bar), .fold (crease "
                  "pattern, FOLD with M/V) or .json (the folded preset); repeatable")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  CLI::Option* scale = sub->add_option("--scale", o->scale, "Crease pattern drawings: millimetres per model unit "
                                                            "(default: the pattern fills about 170 x 220 mm)")
                           ->check(positive_number());
  sub->add_flag("--json", o->json, "Print JSON instead of text");
  sub->callback([o, scale, &context] {
    const std::optional<double> drawing_scale = scale->count() ? std::optional<double>(o->scale) : std::nullopt;
    if (drawing_scale && !(*drawing_scale > 0.0)) {
      throw InvalidInputError("--scale", "must be a positive number of millimetres per model unit");
    }
    for (const std::string& path : o->outputs) {
      const std::string ext = std::filesystem::path(path).extension().string();
      if (ext != ".svg" && ext != ".pdf" && ext != ".fold" && ext != ".json") {
        throw InvalidInputError("output", "unknown format \"" + ext + "\" for " + path + " (use .svg, .pdf, .fold or .json)");
      }
    }
    context.preset = o->pattern;
    const DevelopedPattern pattern(developed_from_json(parse_json_text(read_text_file(o->pattern))));
    const std::vector<int> fold = fold_choices(o->fold, pattern.strips());
    const std::vector<FlexDirection> directions = pattern.flex_directions();
    const FlexDirection* chosen = nullptr;
    for (const FlexDirection& f : directions) {
      const bool wanted = o->direction.empty() || (o->direction == "up") == (f.direction > 0);
      if (wanted && f.folds && !chosen) chosen = &f;
    }
    nlohmann::json report{{"name", pattern.input().name},
                          {"strips", pattern.strips()},
                          {"profile_vertices", pattern.columns()},
                          {"case", to_string(pattern.motion_case())},
                          {"t_star", pattern.t_star()},
                          {"directions", {direction_json(directions[0]), direction_json(directions[1])}}};
    if (!o->json) {
      context.out << "developed pattern \"" << pattern.input().name << "\": " << pattern.strips() << " strips, "
                  << pattern.columns() << " vertices a profile, case (" << to_string(pattern.motion_case())
                  << "), flat at t* = " << format_human(pattern.t_star()) << '\n';
      for (const FlexDirection& f : directions) {
        context.out << (f.direction > 0 ? "t increasing: " : "t decreasing: ")
                    << (f.folds ? "folds, until t = " + format_human(f.reach) +
                                      (f.flat_at_reach ? " where it is flat again (flat-foldable)" : "")
                                : "no flex: " + f.reason)
                    << '\n';
        if (!f.expansion.empty()) {
          context.out << "  non-expansion <v(P)-v(Q), P-Q> per strip (<= 0 folds):";
          for (std::size_t i = 0; i < f.expansion.size(); ++i) {
            context.out << ' ' << format_human(f.expansion[i]) << (f.strip_folds[i] ? "" : "(!)");
          }
          context.out << '\n';
        }
      }
    }
    if (!chosen) {
      if (o->json) {
        report["folds"] = false;
        context.out << report.dump(2) << '\n';
      } else {
        context.out << "no real flex out of the flat state" << (o->direction.empty() ? "" : " in that direction")
                    << ": t_lambda = t* = t_mu; nothing written\n";
      }
      context.exit_code = static_cast<int>(ExitCode::check_failed);
      return;
    }
    const double span = chosen->reach - pattern.t_star();
    const double t = pattern.t_star() + o->fraction * span, t_near = pattern.t_star() + 1e-3 * o->fraction * span;
    const CreasePattern creases = crease_pattern(pattern, fold, t_near, t);
    if (!creases.contradicted.empty()) {
      refuse_fold_through(context, pattern, fold, *o, creases, span);
      return;
    }
    for (const std::string& path : o->outputs) {
      const std::string ext = std::filesystem::path(path).extension().string();
      std::string text;
      if (ext == ".svg") text = crease_svg(creases, drawing_scale);
      if (ext == ".pdf") text = crease_pdf(creases, drawing_scale);
      if (ext == ".fold") text = crease_fold(creases).dump(1) + "\n";
      if (ext == ".json") text = preset_to_json(pattern.folded_preset(t, fold)).dump(2) + "\n";
      emit(text, path, o->pattern, context.out);
    }
    // Whether the folded P-hedron can be built: a choice of the strips can make
    // panels pass through each other on the way.
    const Design folded{Assembly(PHedron(pattern.folded_preset(t, fold))), false, "open P-hedron"};
    const BuildabilityReport buildability = assess_for_output(folded);
    if (!buildability.buildable()) {
      context.err << "phedra: warning: the folded P-hedron (strip choices "
                  << (o->fold.empty() ? std::string(pattern.strips(), '+') : o->fold)
                  << ") is not buildable: " << buildability.summary()
                  << "; another --fold may be (phedra check on the .json output names the causes)\n";
    }
    report["folded_buildability"] = buildability.file_json();
    report["folds"] = true;
    report["chosen_direction"] = chosen->direction > 0 ? "up" : "down";
    report["fold"] = o->fold.empty() ? std::string(pattern.strips(), '+') : o->fold;
    report["folded_t"] = t;
    report["mountains"] = creases.mountains;
    report["valleys"] = creases.valleys;
    if (o->json) {
      context.out << report.dump(2) << '\n';
      return;
    }
    context.out << "every one of the 2^" << pattern.strips() << " choices of the strips folds that way (--fold picks one)\n"
                << "folding " << (chosen->direction > 0 ? "up" : "down") << " with strip choices "
                << report["fold"].get<std::string>() << ": " << creases.mountains << " mountain and " << creases.valleys
                << " valley creases; the written state is t = " << format_human(t) << '\n';
    for (const std::string& path : o->outputs) context.out << "wrote " << path << '\n';
  });
}

}  // namespace phedra::cli
