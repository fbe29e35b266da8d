#include "phedra/mechanics_report.h"

#include "phedra/report_values.h"

namespace phedra {

MechanicsReport mechanics_report(const Design& design, const MechanicsRequest& request) {
  const Assembly& a = design.assembly;
  MechanicsReport r;
  r.name = a.name();
  r.t = request.t;
  r.fraction = (request.t - a.flexion_interval().lower.t) / a.flexion_interval().width();
  r.model_size = a.model_size();
  r.stiffness = request.stiffness;
  AssemblyConfiguration configuration;
  std::vector<Points> rates;
  const bool finite = a.evaluate_rate(request.t, configuration, rates);
  r.model = std::make_unique<BarHingeModel>(design, configuration, request.stiffness);
  std::optional<Eigen::VectorXd> velocity;
  if (finite) {
    Points v;
    r.model->node_rates(rates, v);
    velocity = flatten(v);
  }
  r.modes = analyze_modes(*r.model, velocity, request.modes);
  r.mobility = mobility(r.model->mesh(), velocity);
  if (request.over_interval) r.over_interval = modes_over_interval(design, *request.over_interval, request.stiffness, request.modes);
  if (request.energy) {
    EnergyOptions e = *request.energy;
    e.stiffness = request.stiffness;
    r.energy = energy_landscape(design, e);
  }
  return r;
}

nlohmann::json MechanicsReport::to_json() const {
  nlohmann::json stiffness_json;
  if (stiffness.material) {
    stiffness_json = {{"material",
                       {{"E", stiffness.material->youngs_modulus},
                        {"nu", stiffness.material->poisson},
                        {"thickness", stiffness.material->thickness},
                        {"length_scale", optional_json(stiffness.material->length_scale)}}}};
  } else {
    stiffness_json = {{"bar_EA", stiffness.bar}, {"fold_KF", stiffness.fold_value()}, {"bend_KB", stiffness.bend}};
  }
  nlohmann::json j = {
      {"name", name},
      {"t", t},
      {"fraction", fraction},
      {"panels", to_string(stiffness.panels)},
      {"stiffness", stiffness_json},
      {"nodes", modes.nodes},
      {"bars", modes.bars},
      {"hinges", {{"fold", modes.folds}, {"bend", modes.bends}}},
      {"rigid_body_modes", modes.rigid_body_modes},
      {"largest_eigenvalue", modes.largest_eigenvalue},
      {"eigenvalues", std::vector<double>(modes.eigenvalues.data(), modes.eigenvalues.data() + modes.eigenvalues.size())},
      {"motion_alignment", optional_json(modes.motion_alignment)},
      {"motion_in_span", modes.motion_in_span},
      {"gap", optional_json(modes.gap)},
      {"motion_stiffness", optional_json(modes.motion_stiffness)},
      {"mobility", mobility.to_json()}};
  if (over_interval) j["over_interval"] = over_interval->to_json();
  if (energy) j.update(energy->to_json());
  return j;
}

}  // namespace phedra
