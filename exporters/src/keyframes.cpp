#include "phedra/keyframes.h"

#include "phedra/interval_check.h"

#include <algorithm>
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

/// Largest distance of a panel corner (as opening() last placed them) from its exact place.
double vertex_error(const PanelTree& tree, const OpeningScratch& scratch, const Points& truth) {
  double worst = 0.0;
  for (std::size_t f = 0; f < tree.panels(); ++f) {
    for (int k = 0; k < 4; ++k) worst = std::max(worst, (scratch.corners[f][k] - truth[tree.face(f)[k]]).norm());
  }
  return worst;
}

/// What an interval is judged by: the hinge opening and the vertex error, and where.
struct Deviation {
  double opening = 0.0, error = 0.0, opening_t = 0.0, error_t = 0.0;
  double worst() const { return std::max(opening, error); }
};

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
  std::vector<RigidPose> half, quarter;
  OpeningScratch scratch;
  // The deviations of the poses interpolated at fraction s of [a, b].
  auto deviation_at = [&](const std::vector<RigidPose>& poses, double t, Deviation& d) {
    const double o = opening(tree, poses, groups, scratch);
    const double e = vertex_error(tree, scratch, positions(t));
    if (o > d.opening) d.opening = o, d.opening_t = t;
    if (e > d.error) d.error = e, d.error_t = t;
  };
  // At 1/4, 1/2 and 3/4 (as slerp and lerp give them, keyframes being sign-aligned).
  auto coarse = [&](double a, double b) {
    Deviation d;
    const std::vector<RigidPose>& pa = frames.at(a);
    const std::vector<RigidPose>& pb = frames.at(b);
    halfway_poses(pa, pb, half);
    for (double s : {0.25, 0.5, 0.75}) {
      if (s != 0.5) halfway_poses(s < 0.5 ? pa : half, s < 0.5 ? half : pb, quarter);
      deviation_at(s == 0.5 ? half : quarter, a + s * (b - a), d);
    }
    return d;
  };
  // At k/16, k = 1..15: what the interval is judged by.
  auto fine = [&](double a, double b) {
    Deviation d;
    for (int k = 1; k < 16; ++k) {
      const double s = k / 16.0;
      deviation_at(interpolate_poses(frames.at(a), frames.at(b), s), a + s * (b - a), d);
    }
    return d;
  };
  while (!pending.empty()) {
    std::vector<std::pair<double, double>> next;
    for (const auto& [a, b] : pending) {
      Deviation d = coarse(a, b);
      if (d.worst() <= result.tolerance) d = fine(a, b);
      const double mid = 0.5 * (a + b);
      const bool wide = b - a >= 2.0 * options.minimum_spacing * (hi - lo);
      const bool split = d.worst() > result.tolerance && wide && mid > a && mid < b && frames.size() < options.maximum;
      if (split) {
        std::vector<RigidPose> poses = tree.local_poses(positions(mid));
        align_signs(frames.at(a), poses);
        frames[mid] = std::move(poses);
        next.push_back({a, mid});
        next.push_back({mid, b});
      } else {
        settled += b - a;
        if (!wide && d.worst() > result.tolerance) {
          result.narrow_vertex_error = std::max(result.narrow_vertex_error, d.worst());
          result.narrow_width += b - a;
        } else {
          if (d.opening > result.max_opening) result.max_opening = d.opening, result.opening_t = d.opening_t;
          if (d.error > result.max_vertex_error) result.max_vertex_error = d.error, result.vertex_error_t = d.error_t;
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
