#pragma once
// Runs the `phedra` command in-process for tests: exit code and both outputs.

#include "cli.h"

#include <sstream>
#include <string>
#include <vector>

namespace phedra::test {

struct Run {
  int code;
  std::string out, err;
};

inline Run phedra_cli(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = cli::run(args, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace phedra::test
