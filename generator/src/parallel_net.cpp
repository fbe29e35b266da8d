#include "phedra/parallel_net.h"

#include "phedra/errors.h"
#include "phedra/tolerances.h"

#include <string>

namespace phedra {

ParallelNet build_parallel_net(const AxialNet& axial, const Points& trajectory) {
  ParallelNet net;
  net.rows = axial.rows;
  net.columns = axial.columns;
  const std::size_t n = net.columns;
  net.vertices.assign(net.rows * n, Vec3::Zero());
  net.transversal_scales.assign(net.rows * n, 1.0);
  for (std::size_t j = 0; j < n; ++j) {
    net.vertices[j] = axial.vertex(0, j);
    net.vertices[n + j] = axial.vertex(1, j);
  }
  for (std::size_t i = 2; i < net.rows; ++i) {
    net.vertices[i * n] = trajectory[i];
    net.transversal_scales[i * n] = 1.0 / axial.edge_scale[i];
    for (std::size_t j = 0; j + 1 < n; ++j) {
      // G[i][j+1] = G[i][j] + p u = G[i-1][j+1] + q v: solve p u - q v = w.
      const Vec3 u = axial.vertex(i, j + 1) - axial.vertex(i, j);
      const Vec3 v = axial.vertex(i, j + 1) - axial.vertex(i - 1, j + 1);
      const Vec3 w = net.vertices[(i - 1) * n + j + 1] - net.vertices[i * n + j];
      const Vec3 uv = u.cross(v);
      const double uv2 = uv.squaredNorm();
      if (!(uv2 > tolerance::parallel_sine * tolerance::parallel_sine * u.squaredNorm() * v.squaredNorm())) {
        throw InvalidInputError("", "face (" + std::to_string(i - 1) + ", " + std::to_string(j) +
                                        ") of the axial net is degenerate (its edges at V_{" + std::to_string(i) +
                                        "," + std::to_string(j + 1) + "} are parallel)");
      }
      const double p = w.cross(v).dot(uv) / uv2;
      const double q = w.cross(u).dot(uv) / uv2;
      net.vertices[i * n + j + 1] = net.vertices[i * n + j] + p * u;
      net.transversal_scales[i * n + j + 1] = q;
    }
  }
  return net;
}

}  // namespace phedra
