#include "phedra/keyframes.h"

#include "phedra/interval_check.h"

#include <map>

namespace phedra {
namespace {

/// Scratch of opening(): world poses and the corners they put every panel's at.
struct OpeningScratch {
  std::vector<RigidPose> world;
  std::vector<std::array<Vec3, 4>> corners;
};

/// Largest distance between vertices that must coincide, with the panels at the
/// local poses `local`.
double opening(const PanelTree& tree, const std::vector<RigidPose>& local,
               const std::vector<std::vector<std::pair<std::size_t, int>>>& groups, OpeningScratch& scratch) {
  tree.world_poses(local, scratch.world);
  scratch.corners.resize(tree.panels());
  for (std::size_t f = 0; f < tree.panels(); ++f) {
    const Mat3 rotation = scratch.world[f].rotation.toRotationMatrix();
    const Vec3& translation = scratch.world[f].translation;
    for (int k = 0; k < 4; ++k) scratch.corners[f][k] = rotation * tree.local_vertices(f)[k] + translation;
  }
  double worst = 0.0;
  for (const auto& group : groups) {
    const auto& [f0, k0] = group.front();
    const Vec3& first = scratch.corners[f0][k0];
    for (std::size_t g = 1; g < group.size(); ++g) {
      const auto& [f, k] = group[g];
      worst = std::max(worst, (scratch.corners[f][k] - first).norm());
    }
  }
  return worst;
}

/// Keeps consecutive quaternions in one hemisphere, so that interpolation takes the short way.
void align_signs(const std::vector<RigidPose>& previous, std::vector<RigidPose>& next) {
  for (std::size_t f = 0; f < next.size(); ++f) {
    if (previous[f].rotation.coeffs().dot(next[f].rotation.coeffs()) < 0.0) {
      next[f].rotation.coeffs() = -next[f].rotation.coeffs();
    }
  }
}

/// The poses halfway between a and b: the slerp at 1/2 of unit quaternions in
/// one hemisphere is their normalised sum (no trigonometry), the translation the
/// mean. Nested, this gives the slerp at 1/4 and 3/4 too.
void halfway_poses(const std::vector<RigidPose>& a, const std::vector<RigidPose>& b, std::vector<RigidPose>& out) {
  out.resize(a.size());
  for (std::size_t f = 0; f < a.size(); ++f) {
    out[f].rotation.coeffs() = (a[f].rotation.coeffs() + b[f].rotation.coeffs()).normalized();
    out[f].translation = 0.5 * (a[f].translation + b[f].translation);
  }
}

}  // namespace

std::vector<RigidPose> interpolate_poses(const std::vector<RigidPose>& a, const std::vector<RigidPose>& b, double s) {
  std::vector<RigidPose> out(a.size());
  for (std::size_t f = 0; f < a.size(); ++f) {
    out[f].rotation = a[f].rotation.slerp(s, b[f].rotation);
    out[f].translation = (1.0 - s) * a[f].translation + s * b[f].translation;
  }
  return out;
}

Keyframes choose_keyframes(const PanelTree& tree, const std::function<Points(double)>& positions, double lo,
                           double hi, const std::vector<std::vector<std::pair<std::size_t, int>>>& groups,
                           double model_size, const KeyframeOptions& options, const KeyframeProgress& progress) {
  Keyframes result;
  result.tolerance = options.relative_tolerance * model_size;
  std::map<double, std::vector<RigidPose>> frames;
  const std::vector<double> initial = interval_samples(lo, hi, std::max<std::size_t>(options.initial, 2));
  for (double t : initial) {
    std::vector<RigidPose> poses = tree.local_poses(positions(t));
    if (!frames.empty()) align_signs(frames.rbegin()->second, poses);
    frames[t] = std::move(poses);
  }
  // Intervals still to measure; an interval that passes is settled for good.
  std::vector<std::pair<double, double>> pending;
  for (std::size_t k = 0; k + 1 < initial.size(); ++k) pending.push_back({initial[k], initial[k + 1]});
  double settled = 0.0;
  // The poses interpolated at 1/4, 1/2 and 3/4 of [a, b] (as slerp and lerp
  // would give them, keyframes being sign-aligned), and scratch.
  std::vector<RigidPose> half, quarter;
  OpeningScratch scratch;
  auto measure = [&](double a, double b, double& where) {
    double worst = 0.0;
    const std::vector<RigidPose>& pa = frames.at(a);
    const std::vector<RigidPose>& pb = frames.at(b);
    halfway_poses(pa, pb, half);
    for (double s : {0.25, 0.5, 0.75}) {
      if (s != 0.5) halfway_poses(s < 0.5 ? pa : half, s < 0.5 ? half : pb, quarter);
      const double o = opening(tree, s == 0.5 ? half : quarter, groups, scratch);
      if (o > worst) {
        worst = o;
        where = a + s * (b - a);
      }
    }
    return worst;
  };
  while (!pending.empty()) {
    std::vector<std::pair<double, double>> next;
    for (const auto& [a, b] : pending) {
      double where = a;
      const double worst = measure(a, b, where);
      const double mid = 0.5 * (a + b);
      const bool split = worst > result.tolerance && mid > a && mid < b && frames.size() < options.maximum;
      if (split) {
        std::vector<RigidPose> poses = tree.local_poses(positions(mid));
        align_signs(frames.at(a), poses);
        frames[mid] = std::move(poses);
        next.push_back({a, mid});
        next.push_back({mid, b});
      } else {
        settled += b - a;
        if (worst > result.max_opening) {
          result.max_opening = worst;
          result.opening_t = where;
        }
      }
      if (progress) progress(settled / (hi - lo), frames.size());
    }
    pending = std::move(next);
  }
  for (auto& [t, poses] : frames) {
    result.t.push_back(t);
    result.local.push_back(std::move(poses));
  }
  return result;
}

}  // namespace phedra
