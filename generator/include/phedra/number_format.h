#pragma once
// Shortest round-trip formatting of doubles, for messages and JSON output.

#include <string>

namespace phedra {

/// The shortest decimal text that reads back as exactly `value`
/// ("nan"/"inf" for non-finite values; writers refuse those before calling).
std::string format_number(double value);

/// Appends format_number(value) to `out` without a temporary string.
void append_number(std::string& out, double value);

/// `digits` significant digits, trailing zeros dropped ("0.956194", "1e-15", "12").
std::string format_significant(double value, int digits = 6);

/// A number in text meant for people (the commands' summaries): 6 significant
/// digits, or format_number's full round-trip precision once
/// set_full_precision(true) (the commands' --full-precision). Files and JSON
/// always use format_number.
std::string format_human(double value);
void set_full_precision(bool full);

}  // namespace phedra
