#pragma once
// Values of the reports' files: a figure that may be undefined is null in JSON
// and an empty cell in CSV (never NaN).

#include "phedra/number_format.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace phedra {

inline nlohmann::json optional_json(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

inline std::string csv_number(const std::optional<double>& v) { return v ? format_number(*v) : std::string(); }

}  // namespace phedra
