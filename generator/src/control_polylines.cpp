#include "phedra/control_polylines.h"

#include "phedra/errors.h"

namespace phedra {

std::string signs_to_string(const std::vector<Sign>& signs) {
  std::string text;
  text.reserve(signs.size());
  for (Sign s : signs) text.push_back(s == Sign::plus ? '+' : '-');
  return text;
}

std::vector<Sign> signs_from_string(const std::string& text) {
  std::vector<Sign> signs;
  signs.reserve(text.size());
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (c == '+') {
      signs.push_back(Sign::plus);
    } else if (c == '-') {
      signs.push_back(Sign::minus);
    } else {
      throw InvalidInputError("signs[" + std::to_string(k) + "]",
                              std::string("expected '+' or '-', got '") + c + "'");
    }
  }
  return signs;
}

}  // namespace phedra
