#pragma once
// The optimizer's side of repair and of the keep-buildable drag (internal to
// repair/): a design's constraint values as NLopt sees them, and the local
// searches on them (feasibility, towards a target, the nearest feasible point).

#include "phedra/design.h"
#include "phedra/repair.h"

#include <nlohmann/json.hpp>
#include <nlopt.hpp>

#include <chrono>
#include <optional>
#include <random>
#include <string>
#include <cstddef>
#include <utility>
#include <vector>

namespace phedra::repair_search {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);

/// The required part of the interval: from t* this fraction of the way to each limit.
std::pair<double, double> required_range(const Assembly& a, double fraction);

/// How the panel shapes enter the constraints.
enum class ShapeMode {
  /// Every edge of the general net at least `edge_target` of the model size long
  /// and pointing the way its axial edge does, and every axial face simple: then
  /// every panel has its axial face's shape (MATH.md section 9). Stricter than
  /// needed, but the edge lengths move continuously where the panel margins have
  /// local minima (a sign change of an edge scale walks from row to row).
  positive_net,
  /// Every panel's shape margin at least `shape_target` (the exact rule).
  exact,
};

constexpr std::size_t slots_per_face = 5;

/// How much of the motion the constraints see.
enum class MotionMode {
  none,     ///< panel shapes alone
  t_star,   ///< and no collision in the configuration at t* (one snapshot: cheap)
  range,    ///< and none over the required part of the interval (a sweep each)
};

/// The optimizer's view of a design: its constraint values (<= 0 satisfied).
class Problem {
 public:
  /// `input_margin`: the input's t* margin (t_star_margin()); the motion modes
  /// keep t* at least RepairOptions::t_star_margin, or half the input's when smaller.
  Problem(const DesignVariables& variables, const RepairOptions& options, std::size_t panels, double size,
          double input_margin = 1.0)
      : variables_(variables), options_(options), panels_(panels), size_(size),
        margin_target_(std::min(options.t_star_margin, 0.5 * input_margin)) {}

  void set_mode(ShapeMode shapes, MotionMode motion, double fraction) {
    shapes_ = shapes;
    motion_ = motion;
    fraction_ = fraction;
    cached_.clear();
  }
  std::size_t constraints() const { return slots_per_face * panels_ + 4; }
  std::size_t evaluations() const { return evaluations_; }

  /// Constraint values at x: per member face its shape values (ShapeMode; exact
  /// also its size bounds), then the deepest penetration (x 10 over the model
  /// size), the furthest hinge past shut (radians) and the growth's log over its
  /// bound over the part of the motion the mode sees (0 for none), and t*'s
  /// margin from the flexion limits short of its target (the motion modes).
  const std::vector<double>& at(const double* x);

 private:
  const DesignVariables& variables_;
  const RepairOptions& options_;
  std::size_t panels_;
  double size_;
  ShapeMode shapes_ = ShapeMode::exact;
  MotionMode motion_ = MotionMode::none;
  double fraction_ = 1.0;
  double margin_target_ = 0.0;
  std::size_t evaluations_ = 0;
  std::vector<double> cached_x_, cached_;
};

/// Bounds (each variable within half the model size, or a quarter turn, of its
/// start; a fixed one at it), initial steps and stopping rules of a local search.
void configure(nlopt::opt& opt, const DesignVariables& variables, std::vector<double>& x, const RepairOptions& options,
               double seconds_left);

/// Runs `opt` from x, keeping where it stopped when NLopt gives up (round-off, forced stop).
void run_opt(nlopt::opt& opt, std::vector<double>& x);

/// The summed violations of x (0: feasible).
double total_violation(Problem& problem, const std::vector<double>& x);

/// Feasibility: minimise the summed violations with Subplex (Nelder-Mead on
/// subspaces: robust where the margins have kinks), stopping where they vanish.
/// Returns the feasible point, or where the search ended.
std::vector<double> feasible_search(const DesignVariables& variables, Problem& problem, std::vector<double> x,
                                    const RepairOptions& options, double seconds_left, std::size_t evaluations);

/// The feasible point nearest `target` on the segment from `feasible` (found by
/// bisection: the feasible part of the segment is taken as one piece).
std::vector<double> towards(Problem& problem, const std::vector<double>& feasible, const std::vector<double>& target);

/// One local search from the feasible x; returns the nearest feasible design it saw.
std::vector<double> local_search(const DesignVariables& variables, Problem& problem, std::vector<double> x,
                                 const RepairOptions& options, double seconds_left, std::size_t evaluations);

/// Scattered starts: `samples` designs drawn about `center` at radii from 5 % to
/// 60 % of each variable's scale (within its bounds), judged by the problem's
/// current mode; the feasible one nearest the input, else Subplex's feasibility
/// search from the `polish` least violating ones (the nearest feasible result).
/// Empty when none is feasible. For the low-dimensional problems where local
/// searches from the input stall (the feasible designs lie in a far component).
std::optional<std::vector<double>> scatter_search(const DesignVariables& variables, Problem& problem,
                                                  const std::vector<double>& center, std::size_t samples,
                                                  std::size_t polish, std::mt19937_64& rng, const RepairOptions& options,
                                                  double seconds_left);

/// A JSON pointer as the field users read: "/tube/apex_heights/3" -> "tube.apex_heights[3]".
std::string pointer_field(const nlohmann::json::json_pointer& pointer);

/// How far t* lies from the nearer flexion limit, over the interval's length
/// (0: t* is a limit, two profile planes coincide in the input; 0.5: the middle).
double t_star_margin(const Assembly& assembly);

/// Every panel a simple quad (MATH.md section 9) within the size bounds (not
/// oversized, not a sliver: panel_size.h); cheap, no collision test.
bool all_panels_simple(const Design& design, const SizeBounds& bounds = {});

}  // namespace phedra::repair_search
