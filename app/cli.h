#pragma once
// Entry point of the `phedra` command, callable in-process (tests).

#include <iosfwd>
#include <string>
#include <vector>

namespace phedra::cli {

/// Runs `phedra args...` (args without the program name); returns the exit code
/// (docs/cli.md: 0 ok, 1 a check failed, 2 bad input, 3 I/O, 4 internal).
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace phedra::cli
