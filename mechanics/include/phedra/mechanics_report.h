#pragma once
// Everything `phedra mechanics` computes for one request, in one place for the
// command, the Python module and the tests: the model at a configuration, its
// modes against the exact motion, its mobility, and optionally the modes over
// the interval and the energy landscape; its JSON is the command's --json.

#include "phedra/energy_landscape.h"
#include "phedra/mobility.h"
#include "phedra/modes_over_interval.h"
#include "phedra/stiffness_modes.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>

namespace phedra {

struct MechanicsRequest {
  double t = 0.0;  ///< the configuration (in the flexion interval)
  StiffnessOptions stiffness;
  std::size_t modes = 6;
  std::optional<std::size_t> over_interval;  ///< configurations over the interval
  std::optional<EnergyOptions> energy;       ///< its stiffness is `stiffness`
};

struct MechanicsReport {
  std::string name;
  double t = 0.0, fraction = 0.0, model_size = 0.0;
  StiffnessOptions stiffness;
  std::unique_ptr<BarHingeModel> model;
  ModeAnalysis modes;
  Mobility mobility;
  std::optional<ModesOverInterval> over_interval;
  std::optional<EnergyLandscape> energy;

  /// The command's --json: t, panels, nodes, bars, hinges {fold, bend}, rigid_body_modes,
  /// eigenvalues, motion_alignment, gap, motion_stiffness, mobility, ...
  nlohmann::json to_json() const;
};

MechanicsReport mechanics_report(const Design& design, const MechanicsRequest& request);

}  // namespace phedra
