#include "phedra/keyframes.h"

#include "phedra/interval_check.h"

#include <map>

namespace phedra {
namespace {

double opening(const PanelTree& tree, const std::vector<RigidPose>& local,
               const std::vector<std::vector<std::pair<std::size_t, int>>>& groups) {
  const std::vector<RigidPose> world = tree.world_poses(local);
  double worst = 0.0;
  for (const auto& group : groups) {
    const auto& [f0, k0] = group.front();
    const Vec3 first = world[f0].apply(tree.local_vertices(f0)[k0]);
    for (std::size_t g = 1; g < group.size(); ++g) {
      const auto& [f, k] = group[g];
      worst = std::max(worst, (world[f].apply(tree.local_vertices(f)[k]) - first).norm());
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
                           double model_size, const KeyframeOptions& options,
                           const std::function<void(std::size_t)>& progress) {
  Keyframes result;
  result.tolerance = options.relative_tolerance * model_size;
  std::map<double, std::vector<RigidPose>> frames;
  for (double t : interval_samples(lo, hi, std::max<std::size_t>(options.initial, 2))) {
    frames[t] = tree.local_poses(positions(t));
  }
  auto align_all = [&] {
    const std::vector<RigidPose>* previous = nullptr;
    for (auto& [t, poses] : frames) {
      if (previous) align_signs(*previous, poses);
      previous = &poses;
    }
  };
  align_all();
  bool refined = true;
  while (refined && frames.size() < options.maximum) {
    refined = false;
    result.max_opening = 0.0;
    std::vector<double> splits;
    for (auto it = frames.begin(); std::next(it) != frames.end(); ++it) {
      const auto next = std::next(it);
      double worst = 0.0, where = it->first;
      for (double s : {0.25, 0.5, 0.75}) {
        const double o = opening(tree, interpolate_poses(it->second, next->second, s), groups);
        if (o > worst) {
          worst = o;
          where = it->first + s * (next->first - it->first);
        }
      }
      const double mid = 0.5 * (it->first + next->first);
      const bool splittable = mid > it->first && mid < next->first;
      if (worst > result.tolerance && splittable) {
        splits.push_back(mid);
      } else if (worst > result.max_opening) {
        result.max_opening = worst;
        result.opening_t = where;
      }
    }
    for (double t : splits) {
      if (frames.size() >= options.maximum) break;
      frames[t] = tree.local_poses(positions(t));
      refined = true;
      if (progress) progress(frames.size());
    }
    align_all();
  }
  if (refined) {
    // Stopped at the maximum: measure what was reached.
    result.max_opening = 0.0;
    for (auto it = frames.begin(); std::next(it) != frames.end(); ++it) {
      for (double s : {0.25, 0.5, 0.75}) {
        const double o = opening(tree, interpolate_poses(it->second, std::next(it)->second, s), groups);
        if (o > result.max_opening) {
          result.max_opening = o;
          result.opening_t = it->first + s * (std::next(it)->first - it->first);
        }
      }
    }
  }
  for (auto& [t, poses] : frames) {
    result.t.push_back(t);
    result.local.push_back(std::move(poses));
  }
  return result;
}

}  // namespace phedra
