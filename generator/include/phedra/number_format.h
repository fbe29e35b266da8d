#pragma once
// Shortest round-trip formatting of doubles, for messages and JSON output.

#include <string>

namespace phedra {

/// The shortest decimal text that reads back as exactly `value`
/// ("nan"/"inf" for non-finite values; writers refuse those before calling).
std::string format_number(double value);

/// Appends format_number(value) to `out` without a temporary string.
void append_number(std::string& out, double value);

}  // namespace phedra
