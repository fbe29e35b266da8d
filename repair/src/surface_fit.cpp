// The fit target (optimize.h): points read from a file, and their RMS distance
// to a design's panels at t* after the best rigid motion of the points.

#include "phedra/optimize.h"

#include "phedra/errors.h"
#include "phedra/files.h"
#include "phedra/triangle_overlap.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace phedra {
namespace {

struct SurfaceTriangle {
  Vec3 a, b, c;
  Vec3 centre;          ///< of its bounding sphere (the corners' mean)
  double radius = 0.0;  ///< the farthest corner from it
  SurfaceTriangle(const Vec3& a_, const Vec3& b_, const Vec3& c_) : a(a_), b(b_), c(c_), centre((a_ + b_ + c_) / 3.0) {
    radius = std::sqrt(std::max({(a - centre).squaredNorm(), (b - centre).squaredNorm(), (c - centre).squaredNorm()}));
  }
};

/// The closest point of the panels to p: triangles whose bounding sphere is
/// farther than the best so far are skipped.
Vec3 closest_on_surface(const Vec3& p, const std::vector<SurfaceTriangle>& triangles) {
  Vec3 best = triangles.front().a;
  double distance = std::numeric_limits<double>::infinity();
  for (const SurfaceTriangle& t : triangles) {
    const double reach = (t.centre - p).norm() - t.radius;
    if (reach > 0.0 && reach * reach >= distance) continue;
    const Vec3 q = closest_on_triangle(p, t.a, t.b, t.c);
    const double d = (q - p).squaredNorm();
    if (d < distance) distance = d, best = q;
  }
  return best;
}

}  // namespace

std::vector<Vec3> FitTarget::read_points(const std::string& path) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(read_text_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInputError("--fit", path + " is not JSON: " + e.what());
  }
  const nlohmann::json& list = document.is_object() ? document.value("points", nlohmann::json()) : document;
  if (!list.is_array()) throw InvalidInputError("--fit", path + ": expected {\"points\": [[x, y, z], ...]}");
  std::vector<Vec3> points;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const nlohmann::json& p = list[k];
    if (!p.is_array() || p.size() != 3 || !std::all_of(p.begin(), p.end(), [](const nlohmann::json& v) { return v.is_number(); })) {
      throw InvalidInputError("--fit", path + ": points[" + std::to_string(k) + "] is not three numbers [x, y, z]");
    }
    points.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  }
  check_points(points, "--fit", path + ": ");
  return points;
}

void FitTarget::check_points(const std::vector<Vec3>& points, const std::string& field, const std::string& where) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!points[k].allFinite()) throw InvalidInputError(field, where + "points[" + std::to_string(k) + "] is not finite");
  }
  if (points.size() < 3) throw InvalidInputError(field, where + "at least 3 points, found " + std::to_string(points.size()));
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Mat3 spread = Mat3::Zero();
  for (const Vec3& p : points) spread += (p - centroid) * (p - centroid).transpose();
  const Vec3 values = Eigen::SelfAdjointEigenSolver<Mat3>(spread, Eigen::EigenvaluesOnly).eigenvalues();  // ascending
  const double scale = std::max(1.0, centroid.squaredNorm()) * static_cast<double>(points.size());
  if (!(values(2) > 1e-24 * scale)) {
    throw InvalidInputError(field, where + "the " + std::to_string(points.size()) +
                                       " points all coincide: there is no surface to fit (the points' rigid alignment is undefined)");
  }
  if (!(values(1) > 1e-12 * values(2))) {  // rounding leaves about 1e-16 of the largest
    throw InvalidInputError(field, where + "the " + std::to_string(points.size()) +
                                       " points lie on one line: they span no surface to fit (the points' turn about "
                                       "the line is undefined)");
  }
}

namespace {

/// best_fit from the given turn (one descent) or from every start (none given).
SurfaceFit fit(const Design& design, const std::vector<Vec3>& points, const Mat3* start) {
  const Assembly& a = design.assembly;
  const AssemblyConfiguration c = a.evaluate(a.t_star());
  std::vector<SurfaceTriangle> triangles;
  Vec3 surface_centroid = Vec3::Zero();
  std::size_t count = 0;
  for (std::size_t m = 0; m < a.member_count(); ++m) {
    const GridTopology& g = a.topology(m);
    const Points& x = c.members[m];
    for (std::size_t f = 0; f < g.face_count(); ++f) {
      const Quad q = g.face(f);
      triangles.emplace_back(x[q[0]], x[q[1]], x[q[2]]);
      triangles.emplace_back(x[q[0]], x[q[2]], x[q[3]]);
    }
    for (const Vec3& p : x) surface_centroid += p;
    count += x.size();
  }
  surface_centroid /= static_cast<double>(count);
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  // Iterated closest points: the points moved rigidly (rotation r about their
  // centroid, then to `shift`), matched to their closest surface points, the
  // best rigid motion of those pairs (Kabsch), until the distance settles.
  // Started from the points as given and from the four turns that align their
  // principal axes with the surface's vertices' (a large turn has local minima).
  auto icp = [&](Mat3 r, double& rms) -> Mat3 {
    Vec3 shift = surface_centroid;
    double previous = std::numeric_limits<double>::infinity();
    rms = previous;
    std::vector<Vec3> matched(points.size());
    for (int iteration = 0; iteration < 200; ++iteration) {
      double sum = 0.0;
      for (std::size_t k = 0; k < points.size(); ++k) {
        const Vec3 moved = r * (points[k] - centroid) + shift;
        matched[k] = closest_on_surface(moved, triangles);
        sum += (matched[k] - moved).squaredNorm();
      }
      rms = std::sqrt(sum / static_cast<double>(points.size()));
      if (previous - rms <= 1e-7 * rms + 1e-12) break;
      previous = rms;
      Vec3 target = Vec3::Zero();
      for (const Vec3& q : matched) target += q;
      target /= static_cast<double>(matched.size());
      Mat3 h = Mat3::Zero();
      for (std::size_t k = 0; k < points.size(); ++k) h += (points[k] - centroid) * (matched[k] - target).transpose();
      const Eigen::JacobiSVD<Mat3> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Mat3 d = Mat3::Identity();
      d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
      r = svd.matrixV() * d * svd.matrixU().transpose();
      shift = target;
    }
    return r;
  };
  auto axes_of = [](const std::vector<Vec3>& p, const Vec3& mean) {
    Mat3 spread = Mat3::Zero();
    for (const Vec3& q : p) spread += (q - mean) * (q - mean).transpose();
    Mat3 v = Eigen::SelfAdjointEigenSolver<Mat3>(spread).eigenvectors();
    if (v.determinant() < 0.0) v.col(0) = -v.col(0);
    return v;
  };
  if (start) {  // one descent from the given turn (a search's designs change little between evaluations)
    SurfaceFit f;
    f.turn = icp(*start, f.rms);
    return f;
  }
  std::vector<Vec3> vertices;
  for (const Points& x : c.members) vertices.insert(vertices.end(), x.begin(), x.end());
  const Mat3 from = axes_of(points, centroid), to = axes_of(vertices, surface_centroid);
  // The least-spread axis (a sheet's normal) is well defined; the other two are
  // not when the cloud is nearly round (their order may swap between the points
  // and the panels). So: the points' normal turned onto the panels' (either
  // way up), then spun about it in 15 degree steps (a descent finds the nearest
  // minimum from about 10 degrees away).
  SurfaceFit best;
  best.turn = icp(Mat3::Identity(), best.rms);
  for (const double up : {1.0, -1.0}) {
    const Mat3 align = Eigen::Quaterniond::FromTwoVectors(from.col(0), up * to.col(0)).toRotationMatrix();
    for (int k = 0; k < 24; ++k) {
      const Mat3 spin = Eigen::AngleAxisd(k * std::numbers::pi / 12.0, to.col(0)).toRotationMatrix();
      SurfaceFit f;
      f.turn = icp(spin * align, f.rms);
      if (f.rms < best.rms) best = f;
    }
  }
  return best;
}

}  // namespace

SurfaceFit best_fit(const Design& design, const std::vector<Vec3>& points) { return fit(design, points, nullptr); }

double fit_distance(const Design& design, const std::vector<Vec3>& points, Mat3* start) {
  if (!start) return fit(design, points, nullptr).rms;
  const SurfaceFit f = fit(design, points, start);
  *start = f.turn;
  return f.rms;
}

}  // namespace phedra
