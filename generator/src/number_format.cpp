#include "phedra/number_format.h"

#include <array>
#include <charconv>

namespace phedra {

void append_number(std::string& out, double value) {
  std::array<char, 32> buffer{};
  auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.append(buffer.data(), result.ptr);
}

std::string format_number(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

}  // namespace phedra
