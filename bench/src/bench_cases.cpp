#include "phedra/bench_cases.h"

#include "phedra/tube_array.h"

#include <cmath>

namespace phedra::bench {

ControlPolylines general_open_input(std::size_t profiles, std::size_t n, bool mixed_signs) {
  ControlPolylines in;
  for (std::size_t i = 0; i < profiles; ++i) {
    const double k = static_cast<double>(i);
    const double a = 0.22 * k;
    const double turn = 0.05 * std::sin(1.3 * k);  // off the axis: a general P-hedron
    in.trajectory.push_back(Vec3(3 * std::cos(a), 3 * std::sin(a), 0.35 * k));
    in.directions.push_back(Vec3(std::cos(a + turn), std::sin(a + turn), 0));
  }
  for (std::size_t j = 0; j <= n; ++j) {
    const double k = static_cast<double>(j);
    in.apex_heights.push_back(j % 2 ? 1.0 + 0.3 * std::sin(0.7 * k) : -1.0 + 0.3 * std::cos(0.5 * k));
  }
  in.signs.assign(n - 1, Sign::plus);
  if (mixed_signs) {
    for (std::size_t j = 2; j < in.signs.size(); j += 3) in.signs[j] = Sign::minus;
  }
  return in;
}

ControlPolylines open_input_with_vertices(std::size_t vertices, bool mixed_signs) {
  const std::size_t columns = vertices >= 1000000 ? 1000 : (vertices >= 10000 ? 100 : 10);
  return general_open_input(std::max<std::size_t>(2, vertices / columns), columns - 2, mixed_signs);
}

Design parallelogram_array(std::size_t cells, std::size_t segments) {
  ControlPolylines base;
  for (std::size_t i = 0; i <= segments; ++i) {
    const double k = static_cast<double>(i);
    const double a = 0.2 * k;
    const double r = 3.0 + 0.2 * std::sin(1.7 * k);
    base.trajectory.push_back(Vec3(r * std::cos(a), r * std::sin(a), 0.05 + 0.32 * k));
    base.directions.push_back(Vec3(std::cos(a + 0.2), std::sin(a + 0.2), 0));
  }
  std::vector<double> u, w;
  for (std::size_t k = 0; k <= cells; ++k) {
    u.push_back(-2.0 + 0.6 * static_cast<double>(k) * 3.0 / static_cast<double>(cells));
    w.push_back(3.0 - 0.6 * static_cast<double>(k) * 3.0 / static_cast<double>(cells));
  }
  // make_parallelogram_grid takes the heights and signs of cell (0, 0) from u and w.
  base.apex_heights = {u[0], w[0], u[1], w[1], u[0], w[0]};
  base.signs.assign(4, Sign::plus);
  TubeGrid grid = make_parallelogram_grid(base, u, w);
  return Design{std::move(grid.assembly), false,
                std::to_string(cells) + " x " + std::to_string(cells) + " grid of parallelogram cells"};
}

Design open_design_with_panels(std::size_t panels) {
  const std::size_t n = 99;  // 100 faces a strip with the boundary columns
  const std::size_t profiles = std::max<std::size_t>(2, panels / (n + 1) + 1);
  return Design{Assembly(PHedron(general_open_input(profiles, n)), "P-hedron"), false, "open P-hedron"};
}

}  // namespace phedra::bench
