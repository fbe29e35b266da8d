#pragma once
// Metamaterial figures of a design over its flexion interval (issue 7, item 4):
// the extents along the principal directions, the enclosed volume of every tube
// and of the whole array, deployment ratios and effective Poisson's ratios.
//
// Principal directions: the eigenvectors of the covariance of the mesh's
// vertices at t*, largest spread first; they stay fixed while the design folds
// (the motion frame keeps the axis and profile plane 0 fixed). The enclosed
// volume of a tube is that of its side panels closed by its first and last
// profile (both planar: profile i lies in plane pi_i); an array's is the sum of
// its tubes'. Poisson's ratio nu_jk = -(dL_k / L_k) / (dL_j / L_j), the
// derivatives taken in t by central differences of the exact motion; it is
// undefined (empty) where L_j does not change.

#include "phedra/design.h"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct MetricsOptions {
  std::size_t samples = 101;  ///< evenly spread over [t_lambda, t_mu], limits included (>= 2); t* is added
};

struct MetricsSample {
  double t = 0.0;
  std::array<double, 3> extent{};                 ///< along the principal directions
  std::optional<double> volume;                   ///< of all tubes (none for open P-hedra)
  std::vector<std::optional<double>> member_volume;  ///< per member (none for open members)
  std::array<std::optional<double>, 3> poisson;   ///< nu_12, nu_13, nu_23
};

struct MetricsReport {
  std::string name, kind;
  double t_star = 0.0, t_lambda = 0.0, t_mu = 0.0;
  std::array<Vec3, 3> directions;  ///< principal directions (unit, user frame)
  std::vector<MetricsSample> samples;  ///< in increasing t; one of them is t*
  MetricsSample at_t_star;
  /// Largest over smallest over the interval: extents and volume.
  std::array<double, 3> extent_deployment{};
  std::optional<double> volume_deployment;
  /// For the plots: the buildable part of the interval around t* (buildability.h),
  /// none when nothing is buildable; known once the command has assessed it.
  bool buildability_known = false;
  std::optional<std::pair<double, double>> buildable;
  /// The Poisson plot shows values within +-this (beyond: marked at the edge).
  double poisson_clip = 10.0;

  nlohmann::json to_json() const;
  std::string to_csv() const;
  /// Two plots against t: extents and volume relative to t*, and Poisson's ratios;
  /// round ticks, axis labels with units, the share of the interval, the parts
  /// that are not buildable shaded.
  std::string to_svg() const;
};

std::ostream& operator<<(std::ostream& out, const MetricsReport& report);

MetricsReport metamaterial_metrics(const Design& design, const MetricsOptions& options = {});

/// Volume enclosed by a tube member's side panels and its end profiles (0 for an open member).
double enclosed_volume(const GridTopology& topology, const Points& positions);

}  // namespace phedra
