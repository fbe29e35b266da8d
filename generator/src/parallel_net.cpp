#include "phedra/parallel_net.h"

#include "phedra/errors.h"
#include "phedra/tolerances.h"

#include <algorithm>
#include <string>

namespace phedra {

void build_parallel_row(std::size_t i, std::size_t n, const Vec3* previous_axial, const Vec3* axial,
                        const Vec3* previous_general, const Vec3& trajectory, double edge_scale, Vec3* general,
                        double* scales) {
  if (i < 2) {  // rows 0 and 1 are those of the axial net
    std::copy(axial, axial + n, general);
    std::fill(scales, scales + n, 1.0);
    return;
  }
  general[0] = trajectory;
  scales[0] = 1.0 / edge_scale;
  for (std::size_t j = 0; j + 1 < n; ++j) {
    // G[i][j+1] = G[i][j] + p u = G[i-1][j+1] + q v: solve p u - q v = w.
    const Vec3 u = axial[j + 1] - axial[j];
    const Vec3 v = axial[j + 1] - previous_axial[j + 1];
    const Vec3 w = previous_general[j + 1] - general[j];
    const Vec3 uv = u.cross(v);
    const double uv2 = uv.squaredNorm();
    if (!(uv2 > tolerance::parallel_sine * tolerance::parallel_sine * u.squaredNorm() * v.squaredNorm())) {
      throw InvalidInputError("", "face (" + std::to_string(i - 1) + ", " + std::to_string(j) +
                                      ") of the axial net is degenerate (its edges at V_{" + std::to_string(i) + "," +
                                      std::to_string(j + 1) + "} are parallel)");
    }
    const double p = w.cross(v).dot(uv) / uv2;
    const double q = w.cross(u).dot(uv) / uv2;
    general[j + 1] = general[j] + p * u;
    scales[j + 1] = q;
  }
}

ParallelNet build_parallel_net(const AxialNet& axial, const Points& trajectory) {
  ParallelNet net;
  net.rows = axial.rows;
  net.columns = axial.columns;
  const std::size_t n = net.columns;
  net.vertices.assign(net.rows * n, Vec3::Zero());
  net.transversal_scales.assign(net.rows * n, 1.0);
  for (std::size_t i = 0; i < net.rows; ++i) {
    const std::size_t previous = i == 0 ? 0 : (i - 1) * n;
    build_parallel_row(i, n, &axial.vertices[previous], &axial.vertices[i * n], &net.vertices[previous], trajectory[i],
                       axial.edge_scale[i], &net.vertices[i * n], &net.transversal_scales[i * n]);
  }
  return net;
}

}  // namespace phedra
