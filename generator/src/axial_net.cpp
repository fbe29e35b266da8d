#include "phedra/axial_net.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/tolerances.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace phedra {
namespace {

std::string vertex_name(std::size_t i, std::size_t j) {
  return "V_{" + std::to_string(i) + "," + std::to_string(j) + "}";
}

/// Step 1: translate the trajectory from point i on along edge i so that the
/// translated profile plane pi_i contains the z-axis.
void build_axial_trajectory(const CanonicalInput& in, AxialColumn& net) {
  const std::size_t rows = in.trajectory.size();
  net.edge_scale.assign(rows, 1.0);
  net.vertices.assign(rows, Vec3::Zero());
  const double eps = tolerance::scaled(tolerance::coincident, in.scale);
  net.vertices[0] = in.trajectory[0];
  net.vertices[1] = in.trajectory[1];  // pi_1 contains the axis by the choice of frame
  for (std::size_t i = 2; i < rows; ++i) {
    const Vec3 edge = in.trajectory[i] - in.trajectory[i - 1];
    const Vec3& d = in.directions[i];
    const Vec3 normal(-d.y(), d.x(), 0.0);
    const double along = normal.dot(edge);
    if (std::abs(along) <= tolerance::edge_plane_sine * normal.norm() * edge.norm()) {
      throw InvalidInputError("trajectory[" + std::to_string(i) + "]",
                              "the edge from trajectory[" + std::to_string(i - 1) +
                                  "] is parallel to profile plane " + std::to_string(i) +
                                  ", so the plane cannot be translated onto the axis (MATH.md section 2, step 1)");
    }
    const Vec3& previous = net.vertices[i - 1];
    const double k = -normal.dot(previous) / along;
    net.edge_scale[i] = k;
    const Vec3 axial = previous + k * edge;
    if (axial.head<2>().norm() <= eps) {
      throw InvalidInputError("trajectory[" + std::to_string(i) + "]",
                              "the axial net puts " + vertex_name(i, 0) +
                                  " on the axis (profile planes " + std::to_string(i - 1) + " and " +
                                  std::to_string(i) + " meet the trajectory there); the P-hedron is degenerate");
    }
    net.vertices[i] = axial;
  }
}

/// Paper, Remark 1: an axial trajectory vertex equidistant from S_0 and S_1 (a
/// scissor-like linkage) allows only '+' signs; a '-' sends vertices to infinity.
void check_scissor_case(const CanonicalInput& in, const AxialColumn& net) {
  const auto minus = std::find(in.signs.begin(), in.signs.end(), Sign::minus);
  if (minus == in.signs.end()) return;
  const double eps = tolerance::scaled(tolerance::scissor, in.scale);
  const Vec3 s0(0, 0, in.heights[0]), s1(0, 0, in.heights[1]);
  for (std::size_t i = 0; i < net.vertices.size(); ++i) {
    const Vec3& v = net.vertices[i];
    if (std::abs((v - s0).norm() - (v - s1).norm()) <= eps) {
      throw InvalidInputError("signs[" + std::to_string(minus - in.signs.begin()) + "]",
                              vertex_name(i, 0) + " of the axial net is equidistant from S_0 and S_1 (a scissor-like "
                              "linkage), which allows only '+' signs (paper, Remark 1); a '-' sends vertices to "
                              "infinity");
    }
  }
}

}  // namespace

AxialColumn build_axial_column(const CanonicalInput& in) {
  AxialColumn column;
  build_axial_trajectory(in, column);
  check_scissor_case(in, column);
  return column;
}

void build_axial_row(const CanonicalInput& in, std::size_t i, Vec3* row, double* ratios) {
  const std::size_t n = in.heights.size() - 1;
  const auto& z = in.heights;
  const double eps = tolerance::scaled(tolerance::vanishing_line, in.scale);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double c = z[j + 1];
    const Vec3& x = row[j];
    double ratio;
    if (in.signs[j] == Sign::plus) {
      ratio = (z[j + 2] - c) / (z[j] - c);
    } else {
      const double denominator = 2.0 * (x.z() - c) - (z[j] - c);
      if (std::abs(denominator) <= eps) {
        throw InvalidInputError("signs[" + std::to_string(j) + "]",
                                "the perspective collineation of the '-' apex S_" + std::to_string(j + 1) +
                                    " sends " + vertex_name(i, j + 1) + " to infinity (" + vertex_name(i, j) +
                                    " lies on its vanishing line); change the sign or the apex heights");
      }
      ratio = (z[j + 2] - c) / denominator;
    }
    const Vec3 centre(0.0, 0.0, c);
    row[j + 1] = centre + ratio * (x - centre);
    ratios[j] = ratio;
  }
}

AxialNet build_axial_net(const CanonicalInput& in) {
  AxialNet net;
  AxialColumn column = build_axial_column(in);
  net.rows = in.trajectory.size();
  net.columns = in.heights.size() - 1;
  net.vertices.assign(net.rows * net.columns, Vec3::Zero());
  net.ratios.assign(net.rows * (net.columns - 1), 0.0);
  for (std::size_t i = 0; i < net.rows; ++i) {
    net.vertices[i * net.columns] = column.vertices[i];
    build_axial_row(in, i, &net.vertices[i * net.columns], &net.ratios[i * (net.columns - 1)]);
  }
  net.edge_scale = std::move(column.edge_scale);
  return net;
}

}  // namespace phedra
