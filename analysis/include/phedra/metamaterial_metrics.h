#pragma once
// Metamaterial figures of a design over its flexion interval (issue 7, item 4):
// the extents along the principal directions, the enclosed volume of every tube
// and of the whole array, deployment ratios and effective Poisson's ratios.
//
// Axes and lengths (homogenized_strain.h): three axes fixed at t* (structural
// by default: along the trajectory, across it, normal to both); the length
// along axis k at t is its length at t* (the bounding extent then) times the
// stretch of the best affine map from t* to t, so the curves are as smooth as
// the motion; the bounding extents are kept as information. The enclosed
// volume of a tube is that of its side panels closed by its first and last
// profile (both planar: profile i lies in plane pi_i); an array's is the sum of
// its tubes'. Poisson's ratio nu_jk = -(d ln L_k) / (d ln L_j), from the
// derivative of the motion; undefined (empty) where L_j does not change.

#include "phedra/design.h"
#include "phedra/homogenized_strain.h"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

struct MetricsOptions {
  std::size_t samples = 101;  ///< evenly spread over [t_lambda, t_mu], limits included (>= 2); t* is added
  MetricsAxes axes = MetricsAxes::structural;
};

struct MetricsSample {
  double t = 0.0;
  std::array<std::optional<double>, 3> length;    ///< along the axes: L_k(t*) x stretch_k(t) (none: no spread)
  std::array<double, 3> bounding_extent{};        ///< of the vertices along the axes (information: has corners)
  std::array<std::optional<double>, 3> strain_rate;  ///< d ln(L_k) / dt
  std::optional<double> volume;                   ///< of all tubes (none for open P-hedra)
  std::vector<std::optional<double>> member_volume;  ///< per member (none for open members)
  std::array<std::optional<double>, 3> poisson;   ///< nu_12, nu_13, nu_23
};

struct MetricsReport {
  std::string name, kind;
  double t_star = 0.0, t_lambda = 0.0, t_mu = 0.0;
  MetricsAxes axes = MetricsAxes::structural;
  std::array<Vec3, 3> directions;  ///< the axes (unit, user frame), fixed at t*
  std::vector<MetricsSample> samples;  ///< in increasing t; one of them is t*
  MetricsSample at_t_star;
  /// Largest over smallest over the sampled interval: lengths, bounding extents and volume.
  std::array<std::optional<double>, 3> extent_deployment;
  std::array<std::optional<double>, 3> bounding_extent_deployment;
  std::optional<double> volume_deployment;
  double flexion_width() const { return t_mu - t_lambda; }

  /// The figures by the names `phedra optimize --target` takes (figure_names()):
  /// none where undefined.
  std::optional<double> figure(const std::string& wanted) const;
  /// For the plots: the buildable part of the interval around t* (buildability.h),
  /// none when nothing is buildable; known once the command has assessed it.
  bool buildability_known = false;
  std::optional<std::pair<double, double>> buildable;
  /// The Poisson plot (a symmetric log scale) shows values within +-this
  /// (beyond: marked at the edge).
  double poisson_clip = 1e6;

  nlohmann::json to_json() const;
  std::string to_csv() const;
  /// Two plots against t: extents and volume relative to t*, and Poisson's ratios;
  /// round ticks, axis labels with units, the share of the interval, the parts
  /// that are not buildable shaded.
  std::string to_svg() const;
};

std::ostream& operator<<(std::ostream& out, const MetricsReport& report);

MetricsReport metamaterial_metrics(const Design& design, const MetricsOptions& options = {});

/// poisson.nu_12, poisson.nu_13, poisson.nu_23 (at t*), extent_deployment.0|1|2,
/// flexion_width (t_mu - t_lambda), volume_ratio (largest / smallest enclosed volume).
const std::vector<std::string>& figure_names();
/// Whether the figure needs the samples over the interval (not t* alone).
bool figure_needs_interval(const std::string& name);

/// The extent of every member's vertices along each of the axes (max - min of
/// the projections): at t* the metrics' lengths L_k(t*).
std::array<double, 3> axis_extents(const std::vector<Points>& members, const std::array<Vec3, 3>& axes);

/// Volume enclosed by a tube member's side panels and its end profiles (0 for an open member).
double enclosed_volume(const GridTopology& topology, const Points& positions);

}  // namespace phedra
