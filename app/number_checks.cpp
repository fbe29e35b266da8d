#include "number_checks.h"

#include "phedra/number_format.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

namespace phedra::cli {
namespace {

/// The value as the user typed it, at most 20 characters.
std::string shown(const std::string& text) { return text.size() <= 20 ? text : text.substr(0, 17) + "..."; }

/// The text as a double (inf and nan included); none when it is not all a number.
std::optional<double> parsed(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  if (errno == ERANGE && std::isinf(value)) return value;  // beyond the largest double
  return value;
}

/// "" when `text` is a finite number for which `ok` holds, else "must be WHAT (got TEXT)".
template <class Ok>
std::string check(const std::string& text, const std::string& what, const Ok& ok) {
  const std::optional<double> value = parsed(text);
  if (value && std::isfinite(*value) && ok(*value)) return {};
  return "must be " + what + " (got " + shown(text) + ")";
}

std::string bound(double v) { return format_significant(v, 6); }

}  // namespace

CLI::Validator finite_number() {
  return CLI::Validator([](std::string& text) { return check(text, "a number", [](double) { return true; }); },
                        "FINITE", "FINITE");
}

CLI::Validator number_inside(double lo, double hi) {
  const std::string range = "(" + bound(lo) + ", " + bound(hi) + ")";
  return CLI::Validator(
      [=](std::string& text) {
        return check(text, "a number in " + range, [=](double v) { return v > lo && v < hi; });
      },
      "in " + range, "RANGE");
}

CLI::Validator positive_number() {
  return CLI::Validator([](std::string& text) { return check(text, "a positive number", [](double v) { return v > 0.0; }); },
                        "POSITIVE", "POSITIVE");
}

CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) { return check(text, "a number, 0 or more", [](double v) { return v >= 0.0; }); },
      "NONNEGATIVE", "NONNEGATIVE");
}

CLI::Validator number_between(double lo, double hi) {
  const std::string range = "[" + bound(lo) + ", " + bound(hi) + "]";
  return CLI::Validator(
      [=](std::string& text) {
        return check(text, "a number in " + range, [=](double v) { return v >= lo && v <= hi; });
      },
      "in " + range, "RANGE");
}

CLI::Validator zero_or_at_least(double lo) {
  const std::string what = "0 (no bound) or a number, " + bound(lo) + " or more";
  return CLI::Validator(
      [=](std::string& text) { return check(text, what, [=](double v) { return v == 0.0 || v >= lo; }); },
      "0|>=" + bound(lo), "BOUND");
}

CLI::Validator whole_number_between(std::int64_t lo, std::int64_t hi) {
  const std::string range = std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [=](std::string& text) {
        return check(text, "a whole number from " + range, [=](double v) {
          return v == std::floor(v) && v >= static_cast<double>(lo) && v <= static_cast<double>(hi);
        });
      },
      "in " + range, "RANGE");
}

}  // namespace phedra::cli
