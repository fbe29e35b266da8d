#pragma once
// The motion parameters a command was asked for: --t, --fraction (in command-line
// order) and --count.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace phedra {
class Assembly;
}

namespace phedra::cli {

class MotionParameters {
 public:
  /// Registers --t, --fraction and --count on `command`.
  void add_options(CLI::App* command, std::size_t default_count = 0);
  /// The t values: --t and --fraction in the order given, then --count evenly
  /// spread (limits included); `default_count` of them when nothing was given.
  std::vector<double> values(const CLI::App* command, const Assembly& assembly) const;
  /// The same within [range.first, range.second] (a sub-interval, e.g. the
  /// intersection-free one, `what` says which, `restricting_option` asked for it): --count
  /// spreads over it, and a --t or --fraction outside it is an InvalidInputError
  /// naming `restricting_option`.
  std::vector<double> values(const CLI::App* command, const Assembly& assembly, std::pair<double, double> range,
                             const std::string& restricting_option, const std::string& what) const;

 private:
  std::vector<double> t_, fraction_;
  std::size_t count_ = 0;
  std::size_t default_count_ = 0;
  CLI::Option* t_option_ = nullptr;
  CLI::Option* fraction_option_ = nullptr;
};

}  // namespace phedra::cli
