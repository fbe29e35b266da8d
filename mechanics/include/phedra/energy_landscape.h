#pragma once
// The exact energy landscape of the motion (issue 36, item 4; docs/design.md,
// "Mechanics"): the piece was made stress-free at the rest state T0, so its fold
// springs rest at the angles theta(T0); along the exact motion the panels stay
// rigid and planar, so only the folds store energy:
//
//   E(t) = sum over fold hinges of 1/2 L KF (theta(t) - theta(T0))^2,
//
// L the hinge's length (constant along the motion), theta kept continuous from
// T0. dE/dt = sum L KF (theta - theta0) grad(theta) . dX/dt with the exact rate
// of the motion (not differences of E): the generalized force. Equilibria are
// its zeros (refined to 1e-12 of the interval), each a minimum or a maximum;
// two minima make the design bistable, with the barrier between them. The force
// that holds an extension along axis k is dE/dt over dL_k/dt, L_k the lengths of
// `phedra metrics`.

#include "phedra/bar_hinge_model.h"
#include "phedra/homogenized_strain.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct EnergyOptions {
  double rest_t = 0.0;          ///< T0, in the flexion interval
  std::size_t samples = 201;    ///< over [t_lambda, t_mu], both limits included (>= 2); T0 is added
  StiffnessOptions stiffness;   ///< KF (and the panels model, for a material's calibration)
  MetricsAxes axes = MetricsAxes::structural;
  bool two_threads = true;      ///< large models on two threads (the same result, bit for bit)
};

struct EnergySample {
  double t = 0.0;
  double energy = 0.0;
  std::optional<double> rate;                  ///< dE/dt (none at a flexion limit: infinite there)
  std::array<std::optional<double>, 3> length;  ///< L_k (metrics)
  std::array<std::optional<double>, 3> force;   ///< dE/dt / dL_k/dt (none where L_k is stationary or undefined)
};

struct Equilibrium {
  double t = 0.0;
  bool minimum = true;  ///< else a maximum
  double energy = 0.0;
  bool rest = false;    ///< the rest state T0
};

struct EnergyLandscape {
  std::string name;
  double rest_t = 0.0, t_lambda = 0.0, t_mu = 0.0;
  std::size_t folds = 0;
  std::vector<EnergySample> samples;   ///< increasing t, both limits and T0 included
  std::vector<Equilibrium> equilibria;  ///< increasing t
  double largest_energy = 0.0;          ///< over the samples
  bool bistable() const;                ///< two or more minima
  /// Bistable: the highest energy on the way from the rest state to the nearest
  /// other minimum (the barrier to snap over), and back from that minimum.
  std::optional<double> barrier, reverse_barrier;
  std::array<Vec3, 3> axes;             ///< the metrics' axes (unit, user frame)

  nlohmann::json to_json() const;
  std::string to_csv() const;
};

/// The landscape of `design` from the rest state options.rest_t. Throws
/// InvalidInputError("--rest-t") outside the interval, or for samples < 2.
EnergyLandscape energy_landscape(const Design& design, const EnergyOptions& options);

class FoldKernel;

/// The energy landscape's evaluation at one t: the fold springs of the model
/// at the rest state, their angles kept continuous. Const: safe on several
/// threads, each with its own Scratch.
class FoldEnergy {
 public:
  FoldEnergy(const Design& design, double rest_t, const StiffnessOptions& options);
  ~FoldEnergy();

  /// What one evaluation needs: the members' nets at t and their rates, the corner
  /// nodes' positions and rates (read after it), the kernel's scratch.
  struct Scratch {
    std::vector<NetState> states, rates;  ///< the members' canonical nets at t and their rates
    bool finite = false;  ///< the rates exist (not at a flexion limit)
    Points x, v;  ///< the corner nodes' positions and rates
    std::vector<double> frames;  ///< the panels' normals and turns (the fold kernel's)
    /// Each fold's continuous angle is its angle in (-pi, pi] + 2 pi turns.
    std::vector<std::int8_t> turns;
    /// Samples evaluated together (load_lanes, evaluate_lanes): the assembly's
    /// scratch, the corner nodes' positions and rates side by side,
    /// [node][coordinate][lane], the kernel's frames, each lane's turns.
    Assembly::LaneScratch assembly_lanes;
    std::vector<double> lane_x, lane_v, lane_frames;
    std::array<std::vector<std::int8_t>, 4> lane_turns;
  };
  struct Value {
    double energy = 0.0;
    std::optional<double> rate;  ///< dE/dt, none at a flexion limit
    double largest_turn = 0.0;   ///< the largest change of a fold's angle from `near`
  };
  /// The members' nets at t and their rates, and the corner nodes' positions
  /// and rates from them, into `scratch`: the configuration of evaluate(t).
  void nodes_at(double t, Scratch& scratch) const;
  /// E and dE/dt at t; `angles` gets the folds' angles continuous from `near`
  /// (the angles at a t close by; empty: the rest angles).
  Value evaluate(double t, const std::vector<double>& near, std::vector<double>& angles, Scratch& scratch) const;
  /// The same with each fold's whole turns given (an earlier evaluation's
  /// scratch.turns at t): the angles that evaluation gave, bit for bit.
  Value evaluate_turned(double t, const std::vector<std::int8_t>& turns, std::vector<double>& angles,
                        Scratch& scratch) const;

  /// Samples evaluated together: four (SIMD across samples: the fold kernel's
  /// numbers of the four side by side, no gathers).
  static constexpr std::size_t lanes = 4;
  /// The corner nodes' positions and rates of the `lanes` samples ts[0..lanes)
  /// side by side (Assembly::vertices_lanes): each lane what
  /// nodes_at gives, bit for bit. False when one is at a flexion limit (no
  /// rates: such a sample is evaluated alone).
  bool load_lanes(const double* ts, Scratch& scratch) const;
  /// E, dE/dt and the continuous angles of the `lanes` samples loaded (all with
  /// rates), lane l's angles carried from lane l - 1's and lane 0's from `near`
  /// (not empty), its turns into scratch.lane_turns[l]: each lane what evaluate()
  /// gives of its t from those angles, bit for bit.
  std::array<Value, lanes> evaluate_lanes(const std::vector<double>& near,
                                          std::array<std::vector<double>, lanes>& angles, Scratch& scratch) const;

  /// The same with a scratch of its own (tests).
  double energy(double t, std::vector<double>& angles, const std::vector<double>& near = {}) const;
  std::pair<double, std::optional<double>> energy_and_rate(double t, std::vector<double>& angles,
                                                           const std::vector<double>& near = {}) const;
  const std::vector<double>& rest_angles() const { return rest_angles_; }
  const BarHingeModel& model() const { return model_; }
  const Design& design() const { return design_; }

 private:
  Value evaluate_from(double t, const double* near, std::vector<double>& angles, Scratch& s) const;
  const Design& design_;
  BarHingeModel model_;
  std::unique_ptr<FoldKernel> kernel_;
  std::vector<double> rest_angles_, weight_;  ///< weight: k L of each fold
  std::vector<Assembly::NetPlace> places_;    ///< each node's member vertex in the canonical nets
  Assembly::RowPlaces places_by_row_;         ///< the nodes by row (Assembly::vertices_lanes)
};

}  // namespace phedra
