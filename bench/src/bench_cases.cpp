#include "phedra/bench_cases.h"
#include "phedra/preset.h"

#include "phedra/tube_array.h"

#include <cmath>
#include <numbers>

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

Design mechanics_array(std::size_t cells, std::size_t segments) {
  ControlPolylines base;
  for (std::size_t i = 0; i <= segments; ++i) {
    const double a = 0.08 * static_cast<double>(i);
    base.trajectory.push_back(Vec3(5.0 * std::cos(a), 5.0 * std::sin(a), 0.05 + 0.3 * static_cast<double>(i)));
    base.directions.push_back(Vec3(std::cos(a + 0.05), std::sin(a + 0.05), 0));
  }
  std::vector<double> u, w;
  for (std::size_t k = 0; k <= cells; ++k) {
    u.push_back(-2.0 + 0.2 * static_cast<double>(k));
    w.push_back(3.0 - 0.2 * static_cast<double>(k));
  }
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

nlohmann::json unbuildable_default_preset() {
  return nlohmann::json::parse(R"json({"name":"mixed-signs","description":"General open P-hedron with mixed signs on a helical trajectory (the default preset).","trajectory":[[3.0,0.0,0.05],[3.2167598036169744,0.6546888692426079,0.377015115293407],[2.8689054012063293,1.277818395197999,0.6791926581726428],[2.163646846736903,1.8393505559203014,1.0005003751699775],[1.6464170358796948,2.312216636696908,1.3673178189568194],[1.4253243607030766,2.6736220801843062,1.7641831092731612],[1.0440893585695001,2.9061453003547957,2.148008514332518],[0.188103885952204,2.9985774918164374,2.487695112717165],[-0.8125784574043364,2.9464629514128555,2.792724998309569],[-1.4222316965454576,2.7523138658454296,3.104443486905766],[-1.639453240718045,2.4254892114587703,3.458046423546177]],"directions":[[0.9800665778412416,0.19866933079506122,0.0],[0.8177730638851126,0.5755408030573987,0.0],[0.5933074514784253,0.8049759425101944,0.0],[0.4366157869462234,0.8996480726313651,0.0],[0.3804657613697371,0.9247950067043756,0.0],[0.3672319620904478,0.9301293920843486,0.0],[0.3072187498726563,0.951638922977976,0.0],[0.1252026745883706,0.9921311860212432,0.0],[-0.19849652417548783,0.9801015916170374,0.0],[-0.5763440175598852,0.817207179008439,0.0],[-0.8553881157690059,0.5179876170345675,0.0]],"apex_heights":[-1.5,1.0,-0.5,2.2,0.4,3.0,1.6],"signs":"+-+-+"})json");
}

nlohmann::json unbuildable_open_preset(std::size_t strips) {
  // Apex height 1 dragged below height 2: every face of the first column crosses.
  nlohmann::json p = designer_helix_preset(strips);
  p["name"] = "helix-" + std::to_string(strips) + "-crossed";
  p["apex_heights"][1] = -0.7;
  return p;
}

nlohmann::json designer_helix_preset(std::size_t strips) {
  nlohmann::json trajectory = nlohmann::json::array(), directions = nlohmann::json::array();
  for (std::size_t i = 0; i <= strips; ++i) {
    const double q = 0.33 * 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(strips);
    trajectory.push_back({3.0 * std::cos(q), 3.0 * std::sin(q), 1.32 * static_cast<double>(i) / static_cast<double>(strips)});
    const double r = q - 20.0 * std::numbers::pi / 180.0;
    directions.push_back({std::cos(r), std::sin(r), 0.0});
  }
  return {{"name", "helix-" + std::to_string(strips)},
          {"trajectory", trajectory},
          {"directions", directions},
          {"apex_heights", {-1.5, 1.0, -0.5, 2.2, 0.4, 3.0, 1.6, 3.8}},
          {"signs", "++++++"}};
}

nlohmann::json designer_grid_helix_preset(std::size_t vertices) {
  const std::size_t profiles = static_cast<std::size_t>(std::lround(std::sqrt(static_cast<double>(vertices)))) + 1;
  const std::size_t m = profiles - 1, heights = profiles - 2;
  const double s = 10.0 / static_cast<double>(profiles);
  nlohmann::json trajectory = nlohmann::json::array(), directions = nlohmann::json::array(), apex = nlohmann::json::array();
  for (std::size_t i = 0; i <= m; ++i) {
    const double q = 0.33 * 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(m);
    trajectory.push_back({3.0 * std::cos(q), 3.0 * std::sin(q), 1.32 * static_cast<double>(i) / static_cast<double>(m)});
    const double r = q - 20.0 * std::numbers::pi / 180.0;
    directions.push_back({std::cos(r), std::sin(r), 0.0});
  }
  for (std::size_t k = 0; k < heights; ++k) apex.push_back(s * (0.5 * static_cast<double>(k) + (k % 2 ? 2.5 : 0.0) - 1.5));
  return {{"name", "helix-" + std::to_string(profiles) + "x" + std::to_string(heights + 1)},
          {"trajectory", trajectory},
          {"directions", directions},
          {"apex_heights", apex},
          {"signs", std::string(heights - 2, '+')}};
}

}  // namespace phedra::bench
