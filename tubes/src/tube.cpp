#include "phedra/tube.h"

#include "phedra/closed_profile.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/tolerances.h"
#include "phedra/validation.h"

#include <cmath>

namespace phedra {
namespace {

bool violates_symmetry(const TubeHeights& z, double scale) {
  return std::abs(symmetry_defect(z)) > tolerance::scaled(tolerance::coincident, scale);
}

std::string symmetry_sentence(const TubeHeights& z) {
  return "an anti-parallelogram tube needs z_0 + z_2 = z_1 + z_3, here " + format_number(z[0]) + " + " +
         format_number(z[2]) + " = " + format_number(z[0] + z[2]) + " but " + format_number(z[1]) + " + " +
         format_number(z[3]) + " = " + format_number(z[1] + z[3]) + " (defect " + format_number(symmetry_defect(z)) +
         "); it is closed at t* only and opens as it flexes";
}

}  // namespace

const char* to_string(TubeType type) {
  return type == TubeType::parallelogram ? "parallelogram" : "anti-parallelogram";
}

TubeType tube_type_from_string(const std::string& text, const std::string& field) {
  if (text == "parallelogram") return TubeType::parallelogram;
  if (text == "anti-parallelogram") return TubeType::anti_parallelogram;
  throw InvalidInputError(field, "expected \"parallelogram\" or \"anti-parallelogram\", got \"" + text + "\"");
}

Sign tube_sign(TubeType type) { return type == TubeType::parallelogram ? Sign::plus : Sign::minus; }

double symmetry_defect(const TubeHeights& z) { return (z[0] + z[2]) - (z[1] + z[3]); }

void set_tube_profile(ControlPolylines& input, TubeType type, const TubeHeights& z) {
  input.apex_heights = {z[0], z[1], z[2], z[3], z[0], z[1]};
  input.signs.assign(4, tube_sign(type));
}

std::optional<TubeType> recognise_tube(const ControlPolylines& input) {
  if (!has_closed_profile(input) || closed_profile_sides(input) != 4) return std::nullopt;
  return input.signs.front() == Sign::plus ? TubeType::parallelogram : TubeType::anti_parallelogram;
}

TubeHeights tube_heights(const ControlPolylines& input) {
  const auto& h = input.apex_heights;
  return {h.at(0), h.at(1), h.at(2), h.at(3)};
}

std::string tube_symmetry_warning(const ControlPolylines& input) {
  const std::optional<TubeType> type = recognise_tube(input);
  if (type != TubeType::anti_parallelogram) return {};
  const TubeHeights z = tube_heights(input);
  return violates_symmetry(z, input_scale(input)) ? symmetry_sentence(z) : std::string{};
}

PHedron make_tube(ControlPolylines base, TubeType type, const TubeHeights& heights) {
  set_tube_profile(base, type, heights);
  if (type == TubeType::anti_parallelogram && violates_symmetry(heights, input_scale(base))) {
    throw InvalidInputError("tube.apex_heights", symmetry_sentence(heights));
  }
  return PHedron(std::move(base));
}

}  // namespace phedra
