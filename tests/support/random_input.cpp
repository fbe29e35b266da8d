#include "random_input.h"

#include "phedra/errors.h"

#include <algorithm>
#include <cmath>

namespace phedra::test {

double uniform(std::mt19937_64& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

namespace {

Vec3 horizontal(double angle) { return Vec3(std::cos(angle), std::sin(angle), 0.0); }

double sine_between(const Vec3& a, const Vec3& b) {
  return std::abs(a.x() * b.y() - a.y() * b.x()) / (a.head<2>().norm() * b.head<2>().norm());
}

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q.toRotationMatrix();
}

}  // namespace

bool well_inside_interval(double t_star, double lower, double upper, double model_size) {
  return std::min(t_star - lower, upper - t_star) >= 1e-5 * model_size;
}

std::optional<PHedron> draw_phedron(const std::function<ControlPolylines()>& make, int& redrawn, int attempts) {
  for (int attempt = 0; attempt < attempts; ++attempt) {
    try {
      PHedron p(make());
      const FlexionInterval& f = p.flexion_interval();
      if (well_inside_interval(p.t_star(), f.lower.t, f.upper.t, p.model_size())) return p;
    } catch (const InvalidInputError&) {
    }
    ++redrawn;
  }
  return std::nullopt;
}

std::vector<Sign> sign_pattern(std::size_t n, std::size_t k) {
  std::vector<Sign> signs(n - 1);
  for (std::size_t b = 0; b + 1 < n; ++b) signs[b] = (k >> b) & 1 ? Sign::minus : Sign::plus;
  return signs;
}

ControlPolylines random_input(std::mt19937_64& rng, const RandomInputShape& shape) {
  ControlPolylines in;
  in.name = "random";
  const std::size_t m = shape.strips, n = shape.profile_vertices;
  // Local frame: the apex line pi_0 ∩ pi_1 is the z-axis.
  Vec3 v0(uniform(rng, 1.0, 3.0), 0.0, uniform(rng, -0.5, 0.5));
  in.trajectory.push_back(v0);
  in.directions.push_back(Vec3(uniform(rng, 0, 1) < 0.5 ? 1.0 : -1.0, 0, 0));
  // V_1 in another plane through the z-axis.
  const double turn = (uniform(rng, 0, 1) < 0.5 ? 1.0 : -1.0) * uniform(rng, 0.15, 0.6);
  const double radius1 = v0.x() * uniform(rng, 0.7, 1.3);
  Vec3 v1 = radius1 * horizontal(turn);
  v1.z() = v0.z() + uniform(rng, 0.2, 0.7);
  in.trajectory.push_back(v1);
  in.directions.push_back((uniform(rng, 0, 1) < 0.5 ? 1.0 : -1.0) * horizontal(turn));
  double heading = turn + M_PI / 2 + uniform(rng, -0.5, 0.5);
  double direction_angle = turn;
  for (std::size_t i = 2; i <= m; ++i) {
    Vec3 step, d;
    do {
      if (shape.smooth) {
        heading += uniform(rng, -0.3, 0.3);
        direction_angle += (uniform(rng, 0, 1) < 0.5 ? 1.0 : -1.0) * uniform(rng, 0.1, 0.4);
        step = uniform(rng, 0.4, 0.8) * horizontal(heading);
        step.z() = uniform(rng, 0.1, 0.4);
        d = horizontal(direction_angle);
      } else {  // irregular: large random turns
        heading += uniform(rng, -1.2, 1.2);
        direction_angle += (uniform(rng, 0, 1) < 0.5 ? 1.0 : -1.0) * uniform(rng, 0.1, 1.5);
        step = uniform(rng, 0.3, 1.0) * horizontal(heading);
        step.z() = uniform(rng, -0.1, 0.6);
        d = horizontal(direction_angle);
      }
    } while (sine_between(d, in.directions.back()) < 0.1 || sine_between(d, step) < 0.2);
    in.trajectory.push_back(in.trajectory.back() + step);
    in.directions.push_back(uniform(rng, 0.5, 1.5) * d);
  }
  // Apex heights, consecutive triples at least 0.15 apart.
  while (in.apex_heights.size() < n + 1) {
    const double z = uniform(rng, -3.0, 3.0);
    const std::size_t k = in.apex_heights.size();
    bool ok = true;
    for (std::size_t back = 1; back <= 2 && back <= k; ++back) ok = ok && std::abs(z - in.apex_heights[k - back]) > 0.15;
    if (ok) in.apex_heights.push_back(z);
  }
  if (!shape.signs.empty()) {
    in.signs = shape.signs;
  } else {
    for (std::size_t j = 0; j + 1 < n; ++j) in.signs.push_back(uniform(rng, 0, 1) < 0.5 ? Sign::plus : Sign::minus);
  }
  // Scale, then place rigidly.
  for (Vec3& p : in.trajectory) p *= shape.scale;
  for (double& h : in.apex_heights) h *= shape.scale;
  if (shape.random_placement) {
    const Mat3 rotation = random_rotation(rng);
    const Vec3 shift(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5));
    in.axis = rotation * Vec3::UnitZ();
    for (Vec3& p : in.trajectory) p = rotation * p + shape.scale * shift;
    for (Vec3& d : in.directions) d = rotation * d;
    for (double& h : in.apex_heights) h += in.axis.dot(shape.scale * shift);
  }
  return in;
}

}  // namespace phedra::test
