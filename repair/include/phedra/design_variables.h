#pragma once
// The numbers of a preset a repair may change, as one vector: apex heights of
// every kind (keeping each kind's closure condition: a core-schema tube's
// repeated heights, an anti-parallelogram tube's symmetry), the turn of each
// profile direction about the axis (directions stay orthogonal to it), and the
// trajectory's coordinates. Lengths count relative to the model size, turns in
// radians: the distance of a repair (docs/design.md, Repair).

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace phedra {

enum class VariableGroup { apex_heights, directions, trajectory };

std::string to_string(VariableGroup group);

/// "apex_heights,directions" -> the groups; InvalidInputError("--vary", ...) for an unknown name or none.
std::vector<VariableGroup> parse_variable_groups(const std::string& list);

struct DesignVariable {
  enum class Kind { length, turn };
  std::string field;  ///< the preset field: "apex_heights[3]", "trajectory[4][1]", "directions[2]" (a turn)
  Kind kind = Kind::length;
  double start = 0.0;  ///< its value in the input (a turn starts at 0)
  double scale = 1.0;  ///< the model size for lengths, 1 for turns (radians)
  bool fixed = false;  ///< kept at its start (a handle the user holds)
  std::string pointer;  ///< its JSON pointer ("/apex_heights/3", "/directions/2": the vector)
};

class DesignVariables {
 public:
  /// The variables of `preset` (a preset object) in `groups`; those at the JSON
  /// pointers `fixed` ("/trajectory/3", "/apex_heights/2") stay at their start.
  /// InvalidInputError ("--vary") when the groups give nothing to change.
  DesignVariables(const nlohmann::json& preset, const std::vector<VariableGroup>& groups, double model_size,
                  const std::vector<std::string>& fixed = {});

  const std::vector<DesignVariable>& variables() const { return variables_; }
  std::size_t size() const { return variables_.size(); }
  std::vector<double> start() const;

  /// The preset with the variables at x (and every tied value following them);
  /// a variable at its start and a tie none of whose variables moved keep the
  /// preset's own number, bit for bit.
  nlohmann::json preset_at(const std::vector<double>& x) const;

  /// The entries that follow the variables (a closed tube's repeated or
  /// symmetric heights): {JSON pointer, "apex_heights[0] + apex_heights[2] - apex_heights[1]"}.
  std::vector<std::pair<std::string, std::string>> tied_fields() const;

  /// The values of the variables that give `other`, a preset of the same
  /// layout (an atlas row of this design): its numbers at the variables' fields,
  /// a direction's turn from the input's about the axis. InvalidInputError(field)
  /// naming a field `other` lacks.
  std::vector<double> values_of(const nlohmann::json& other, const std::string& field) const;

  /// sqrt(sum ((x_k - start_k) / scale_k)^2): how far x is from the input.
  double distance(const std::vector<double>& x) const;

  /// What the groups asked for but cannot be changed, and why (for reports).
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  struct Length {
    nlohmann::json::json_pointer pointer;
  };
  struct Turn {
    nlohmann::json::json_pointer pointer;  ///< the direction vector
    std::vector<double> direction;         ///< as given
  };
  /// value(target) = sum of coefficient * variable: a tied entry.
  struct Tie {
    nlohmann::json::json_pointer target;
    std::vector<std::pair<std::size_t, double>> terms;
  };
  void add_length(const nlohmann::json::json_pointer& pointer, const std::string& field, double model_size);

  nlohmann::json preset_;
  std::vector<double> axis_{0.0, 0.0, 1.0};
  std::vector<DesignVariable> variables_;
  std::vector<Length> lengths_;  ///< for the length variables, in order
  std::vector<Turn> turns_;      ///< for the turn variables, in order
  std::vector<std::size_t> slot_;  ///< variable k -> index into lengths_ or turns_
  std::vector<Tie> ties_;
  std::vector<std::string> notes_;
};

}  // namespace phedra
