#include "phedra/number_format.h"

#include <array>
#include <charconv>
#include <cstdio>
#include <cstdlib>

namespace phedra {

void append_number(std::string& out, double value) {
  std::array<char, 32> buffer{};
#if defined(__cpp_lib_to_chars)
  auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.append(buffer.data(), result.ptr);
#else
  // No floating-point to_chars (the libc++ of Debian's emscripten): the shortest
  // %g that reads back as the same double, which is what to_chars gives too
  // (only its spelling of exponents may differ).
  int length = 0;
  for (int precision = 1; precision <= 17; ++precision) {
    length = std::snprintf(buffer.data(), buffer.size(), "%.*g", precision, value);
    if (std::strtod(buffer.data(), nullptr) == value) break;
  }
  out.append(buffer.data(), static_cast<std::size_t>(length));
#endif
}

namespace {
bool full_precision = false;
}  // namespace

std::string format_significant(double value, int digits) {
  std::array<char, 40> buffer{};
  const int length = std::snprintf(buffer.data(), buffer.size(), "%.*g", digits, value == 0.0 ? 0.0 : value);
  return std::string(buffer.data(), static_cast<std::size_t>(length));
}

std::string format_human(double value) { return full_precision ? format_number(value) : format_significant(value, 6); }

void set_full_precision(bool full) { full_precision = full; }

std::string format_number(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

}  // namespace phedra
