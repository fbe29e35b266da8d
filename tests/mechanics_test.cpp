// Mechanics (issue 36): the hinge angle and its derivatives, the bar-and-hinge
// model's rules, the stiffness's modes against the exact motion.

#include "support/random_input.h"
#include "support/test_files.h"
#include "phedra/bar_hinge_model.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/hinge_angle.h"
#include "phedra/stiffness_modes.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <filesystem>
#include <numbers>

using namespace phedra;

namespace {

const double pi = std::numbers::pi;

/// Hinge [j k i l] on the x axis, wing i at angle 0 in the xy plane, wing l
/// turned by `dihedral` about the axis (pi: flat), then moved off the axes.
HingeNodes hinge_at(double dihedral, std::mt19937_64& rng) {
  const Vec3 j(0, 0, 0), k(1.3, 0, 0);
  const Vec3 i(0.4, 0.9, 0);
  const Vec3 l(0.7, 0.8 * std::cos(dihedral), 0.8 * std::sin(dihedral));
  const Mat3 r = Eigen::Quaterniond(Eigen::Vector4d(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1),
                                                     test::uniform(rng, -1, 1), test::uniform(rng, -1, 1)).normalized())
                     .toRotationMatrix();
  const Vec3 shift(test::uniform(rng, -2, 2), test::uniform(rng, -2, 2), test::uniform(rng, -2, 2));
  return {r * j + shift, r * k + shift, r * i + shift, r * l + shift};
}

Vec3& node(HingeNodes& x, int a) { return a == 0 ? x.j : a == 1 ? x.k : a == 2 ? x.i : x.l; }

/// MERLIN2's FoldKe: sign(n . r_ij) acos(m . n / |m| |n|), in [0, 2 pi).
double merlin_angle(const HingeNodes& x) {
  const Vec3 rkj = x.k - x.j, rij = x.i - x.j, rkl = x.k - x.l;
  const Vec3 m = rij.cross(rkj), n = rkj.cross(rkl);
  const double s = std::abs(n.dot(rij)) > 1e-8 ? (n.dot(rij) > 0 ? 1.0 : -1.0) : 1.0;
  double he = s * std::acos(std::clamp(m.dot(n) / (m.norm() * n.norm()), -1.0, 1.0));
  return he < 0 ? he + 2 * pi : he;
}

}  // namespace

TEST_CASE("hinge angle: pi flat, MERLIN2's value, continuous across 0 and 2 pi", "[mechanics]") {
  std::mt19937_64 rng(5);
  for (double dihedral : {pi, pi - 1e-9, pi + 1e-9, 0.3, 1.0, 2.5, 4.0, 5.9}) {
    const HingeNodes x = hinge_at(dihedral, rng);
    const double theta = hinge_angle(x);
    CHECK(theta >= 0.0);
    CHECK(theta < 2 * pi);
    CHECK(std::abs(theta - merlin_angle(x)) < 1e-7);
    // The wing i turned by `dihedral` from l about the axis: theta is dihedral or 2 pi - dihedral.
    CHECK(std::min(std::abs(theta - dihedral), std::abs(theta - (2 * pi - dihedral))) < 1e-12);
  }
  CHECK(hinge_angle(hinge_at(pi, rng)) == Approx(pi).margin(1e-14));
  CHECK(continuous_angle(0.01, 6.2) == Approx(0.01 + 2 * pi));
  CHECK(continuous_angle(6.27, 0.02) == Approx(6.27 - 2 * pi));
  CHECK(continuous_angle(3.0, 3.1) == 3.0);
}

TEST_CASE("hinge angle gradient and Hessian against differences: flat, nearly flat and folded", "[mechanics]") {
  std::mt19937_64 rng(17);
  for (double dihedral : {pi, pi + 1e-7, pi - 1e-4, 2.0, 0.35, 5.5, 3.9}) {
    INFO("dihedral " << dihedral);
    const HingeNodes x = hinge_at(dihedral, rng);
    const std::array<Vec3, 4> g = hinge_angle_gradient(x);
    const Eigen::Matrix<double, 12, 12> h = hinge_angle_hessian(x);
    const double step = 1e-6;
    double gradient_error = 0.0, hessian_error = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int c = 0; c < 3; ++c) {
        HingeNodes plus = x, minus = x;
        node(plus, a)(c) += step;
        node(minus, a)(c) -= step;
        const double d = continuous_angle(hinge_angle(plus), hinge_angle(x)) -
                         continuous_angle(hinge_angle(minus), hinge_angle(x));
        gradient_error = std::max(gradient_error, std::abs(d / (2 * step) - g[a](c)));
        const std::array<Vec3, 4> gp = hinge_angle_gradient(plus), gm = hinge_angle_gradient(minus);
        for (int b = 0; b < 4; ++b) {
          for (int e = 0; e < 3; ++e) {
            const double fd = (gp[b](e) - gm[b](e)) / (2 * step);
            hessian_error = std::max(hessian_error, std::abs(fd - h(3 * b + e, 3 * a + c)));
          }
        }
      }
    }
    CHECK(gradient_error < 1e-8);
    CHECK(hessian_error < 1e-7);
    CHECK((h - h.transpose()).cwiseAbs().maxCoeff() < 1e-12);
    // A rigid motion does not change the angle: the gradient is orthogonal to it.
    Vec3 sum = Vec3::Zero(), moment = Vec3::Zero();
    for (int a = 0; a < 4; ++a) {
      sum += g[a];
      moment += node(const_cast<HingeNodes&>(x), a).cross(g[a]);
    }
    CHECK(sum.norm() < 1e-12);
    CHECK(moment.norm() < 1e-11);
  }
}

/// Whether every panel of the design is convex at t (n5b8 needs it).
bool n5b8_models(const Design& design, double t) {
  try {
    BarHingeModel(design, design.assembly.evaluate(t), StiffnessOptions{});
    return true;
  } catch (const InvalidInputError& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("not convex") && Catch::Matchers::Contains("--panels n4b5"));
    return false;
  }
}

TEST_CASE("every shipped preset: six rigid-body modes, and with stiff panels the first mode is the motion", "[mechanics]") {
  std::size_t refused = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::presets)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "preset.schema.json") continue;
    const std::string name = entry.path().filename().string();
    const Design design = load_design(entry.path());
    const auto& interval = design.assembly.flexion_interval();
    for (const PanelModel panels : {PanelModel::n4b5, PanelModel::n5b8}) {
      StiffnessOptions stiff;  // KB / KF = 1e5
      stiff.panels = panels;
      stiff.bar = 1e5;
      stiff.bend = 1000.0;
      stiff.fold = 0.01;
      for (double f : {0.25, 0.5, 0.75}) {
        INFO(name << " " << to_string(panels) << " at fraction " << f);
        const double t = interval.lower.t + f * (interval.upper.t - interval.lower.t);
        if (panels == PanelModel::n5b8 && !n5b8_models(design, t)) {
          ++refused;
          continue;
        }
        const ModeAnalysis a = analyze_modes(design, t, stiff, 2);
        CHECK(a.rigid_body_modes == 6);
        REQUIRE(a.motion_alignment);
        CHECK(*a.motion_alignment >= 0.9999);
      }
    }
  }
  CHECK(refused == 3);  // the anti-parallelogram edge pair (16 bow-ties), at each fraction
}

