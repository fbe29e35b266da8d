#pragma once
// What the writing commands say about buildability: the design's report
// (without field hints: `phedra check` gives those) and a warning on standard
// error when the range they write is not buildable, saying how to get the
// buildable part.

#include "commands.h"
#include "phedra/buildability.h"

#include <optional>
#include <string>

namespace phedra::cli {

/// The buildability of a design for an output (panel causes without hints, the
/// motion swept at `samples_per_side`, by default sweep_samples_for the panel count).
BuildabilityReport assess_for_output(const Design& design, std::optional<std::size_t> samples_per_side = std::nullopt);

/// Warns on context.err when [lo, hi] is not buildable, naming the buildable part
/// when there is one and `restrict_hint`, the option that writes it (for example
/// "--no-self-intersection"; empty: none).
void warn_unless_buildable(Context& context, const BuildabilityReport& report, double lo, double hi,
                           const std::string& restrict_hint);

}  // namespace phedra::cli
