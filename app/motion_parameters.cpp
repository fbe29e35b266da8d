#include "motion_parameters.h"
#include "number_checks.h"

#include "phedra/assembly.h"
#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/number_format.h"

namespace phedra::cli {

void MotionParameters::add_options(CLI::App* command, std::size_t default_count) {
  default_count_ = default_count;
  t_option_ = command->add_option("--t", t_, "A motion parameter t in [t_lambda, t_mu] (repeatable)")
                  ->check(finite_number())
                  ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  fraction_option_ =
      command
          ->add_option("--fraction", fraction_,
                       "A fraction F of the flexion interval: t = t_lambda + F (t_mu - t_lambda); 0 and 1 are the "
                       "limits (repeatable)")
          ->check(number_between(0.0, 1.0))
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  CLI::Option* count = command->add_option("--count", count_,
                                           "N configurations evenly spread over the interval, limits included")
                           ->check(whole_number_between(2, 1000000));
  if (default_count) count->description("N configurations evenly spread over the interval, limits included "
                                        "(default " + std::to_string(default_count) + " when no --t/--fraction)");
}

std::vector<double> MotionParameters::values(const CLI::App* command, const Assembly& a) const {
  return values(command, a, {a.flexion_interval().lower.t, a.flexion_interval().upper.t}, "", "");
}

std::vector<double> MotionParameters::values(const CLI::App* command, const Assembly& a,
                                             std::pair<double, double> range, const std::string& restricting_option,
                                             const std::string& what) const {
  std::vector<double> ts;
  std::size_t next_t = 0, next_f = 0;
  for (const CLI::Option* option : command->parse_order()) {
    if (option == t_option_) ts.push_back(t_.at(next_t++));
    if (option == fraction_option_) ts.push_back(a.t_at_fraction(fraction_.at(next_f++)));
  }
  std::size_t count = count_;
  if (ts.empty() && count == 0) count = default_count_;
  if (count) {
    for (double t : interval_samples(range.first, range.second, count)) ts.push_back(t);
  }
  if (ts.empty()) throw InvalidInputError("", "give at least one --t, --fraction or --count");
  if (!restricting_option.empty()) {
    for (double t : ts) {
      if (t < range.first || t > range.second) {
        throw InvalidInputError(restricting_option, "t = " + format_number(t) + " is outside the " + what + " interval [" +
                                         format_number(range.first) + ", " + format_number(range.second) + "]");
      }
    }
  }
  return ts;
}

}  // namespace phedra::cli
