#pragma once
// One rule for every numeric option's message (issue 39): "--kerf: must be a
// positive number (got -5)". The value is shown as typed, cut to 20 characters;
// CLI11's own range validators printed DBL_MAX in full.

#include <CLI/CLI.hpp>

#include <cstdint>

namespace phedra::cli {

/// A finite number (help: FINITE): nan and inf refused.
CLI::Validator finite_number();
/// A finite number in the open interval (lo, hi).
CLI::Validator number_inside(double lo, double hi);
/// A finite number > 0 (help: POSITIVE).
CLI::Validator positive_number();
/// A finite number >= 0 (help: NONNEGATIVE).
CLI::Validator non_negative_number();
/// A finite number in [lo, hi].
CLI::Validator number_between(double lo, double hi);
/// 0 (no bound) or a finite number >= lo (help: 0|>=lo): a bound that 0 turns off.
CLI::Validator zero_or_at_least(double lo);
/// A whole number in [lo, hi] (for counts).
CLI::Validator whole_number_between(std::int64_t lo, std::int64_t hi);

}  // namespace phedra::cli
