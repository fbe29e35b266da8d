#include "buildability_warning.h"

#include "phedra/number_format.h"

#include <algorithm>
#include <ostream>

namespace phedra::cli {

BuildabilityReport assess_for_output(const Design& design, std::optional<std::size_t> samples_per_side) {
  BuildabilityOptions options;
  options.diagnosis.hints = false;
  options.sweep.samples_per_side = samples_per_side.value_or(0);  // 0: by the panel count
  return assess_buildability(design, nullptr, options);
}

void warn_unless_buildable(Context& context, const BuildabilityReport& r, double lo, double hi,
                           const std::string& restrict_hint) {
  if (r.buildable_over(lo, hi)) return;
  const std::string range = lo == hi ? "t = " + format_human(lo) : "[" + format_human(lo) + ", " + format_human(hi) + "]";
  context.err << "phedra: warning: what is written (" << range << ") is not buildable: " << r.summary();
  const auto part = r.interval();
  if (part && part->second > part->first) {
    context.err << "; " << (restrict_hint.empty() ? "the buildable part is" : restrict_hint + " writes the buildable part")
                << " [" << format_human(part->first) << ", " << format_human(part->second) << "]";
  }
  if (!r.panels_simple()) {
    context.err << "; `phedra check " << context.preset << "` names the cause of each invalid panel and the field to change";
  } else if (r.self_crossing_members.empty()) {
    context.err << "; `phedra intersections " << context.preset << "` shows where the motion collides";
  }
  context.err << '\n';
}

}  // namespace phedra::cli
