#include "phedra/thick_plates.h"

#include "phedra/box_tree.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/panel_shape.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace phedra {
// Named, not anonymous: the unity builds (CMake's, the WebAssembly one) put this
// file in one translation unit with self_intersection.cpp.
namespace thick_detail {

constexpr double full_turn = 2.0 * std::numbers::pi;
constexpr double quarter_turn = 0.5 * std::numbers::pi;
/// A bevel's top inset from its edge is at most this fraction of the panel's depth behind the edge.
constexpr double max_inset_fraction = 0.25;
constexpr double bevel_angle_tolerance = 1e-9;

/// The right-handed area normal of a polygon (Newell), not normalised.
Vec3 area_vector(const std::vector<Vec3>& p) {
  Vec3 a = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) a += p[k].cross(p[(k + 1) % p.size()]);
  return 0.5 * a;
}

/// t of sample k of `samples` from `from` towards `to`, crowding quadratically towards `to`.
double crowded(double from, double to, std::size_t k, std::size_t samples) {
  const double s = 1.0 - static_cast<double>(k) / static_cast<double>(samples);
  return k >= samples ? to : from + (to - from) * (1.0 - s * s);
}

/// An opening continued from `previous` (the turn between the two is under pi).
double continued(double raw, double previous) {
  double step = raw - std::fmod(std::fmod(previous, full_turn) + full_turn, full_turn);
  if (step > std::numbers::pi) step -= full_turn;
  if (step < -std::numbers::pi) step += full_turn;
  return previous + step;
}

/// The faces and edges of the convex hull of a few points (brute force: plates have at most 8).
void hull_axes(const std::vector<Vec3>& p, double eps, std::vector<Vec3>& normals, std::vector<Vec3>& directions) {
  struct Face {
    Vec3 normal;
    double offset;
  };
  std::vector<Face> faces;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        Vec3 normal = (p[j] - p[i]).cross(p[k] - p[i]);
        const double length = normal.norm();
        if (!(length > eps * eps * 1e-3 + 1e-300)) continue;
        normal /= length;
        bool above = false, below = false;
        for (const Vec3& q : p) {
          const double d = normal.dot(q - p[i]);
          above = above || d > eps;
          below = below || d < -eps;
        }
        if (above && below) continue;
        if (above) normal = -normal;
        const bool known = std::any_of(faces.begin(), faces.end(), [&](const Face& f) { return f.normal.dot(normal) > 1.0 - 1e-9; });
        if (!known) faces.push_back({normal, normal.dot(p[i])});
      }
    }
  }
  normals.clear();
  directions.clear();
  for (const Face& f : faces) normals.push_back(f.normal);
  auto add_direction = [&](Vec3 d) {
    const double length = d.norm();
    if (!(length > eps)) return;
    d /= length;
    const bool known = std::any_of(directions.begin(), directions.end(), [&](const Vec3& e) { return std::abs(e.dot(d)) > 1.0 - 1e-9; });
    if (!known) directions.push_back(d);
  };
  for (std::size_t a = 0; a < faces.size(); ++a) {
    for (std::size_t b = a + 1; b < faces.size(); ++b) {
      std::vector<std::size_t> common;
      for (std::size_t i = 0; i < n; ++i) {
        if (std::abs(faces[a].normal.dot(p[i]) - faces[a].offset) <= eps &&
            std::abs(faces[b].normal.dot(p[i]) - faces[b].offset) <= eps) {
          common.push_back(i);
        }
      }
      if (common.size() >= 2) add_direction(faces[a].normal.cross(faces[b].normal));
    }
  }
}

}  // namespace thick_detail
using namespace thick_detail;

std::string to_string(PlateSide side) {
  switch (side) {
    case PlateSide::automatic: return "auto";
    case PlateSide::front: return "front";
    case PlateSide::back: return "back";
  }
  return "auto";
}

PlateSide plate_side_from_string(const std::string& text) {
  if (text == "auto") return PlateSide::automatic;
  if (text == "front") return PlateSide::front;
  if (text == "back") return PlateSide::back;
  throw InvalidInputError("--plate-side", "\"" + text + "\" is not a side (use auto, front or back)");
}

double Solid::volume() const {
  double v = 0.0;
  for (const auto& t : triangles) v += vertices[t[0]].dot(vertices[t[1]].cross(vertices[t[2]]));
  return v / 6.0;
}

ThickPlates::ThickPlates(const Design& design, double thickness, PlateSide side, std::pair<double, double> range,
                         double hinge_gap)
    : design_(design), mesh_(panel_mesh(design)), thickness_(thickness), side_(side) {
  if (!(hinge_gap >= 0.0) || !std::isfinite(hinge_gap)) {
    throw InvalidInputError("--hinge-gap", "the gap at each hinge must be a number >= 0 (got " + format_number(hinge_gap) + ")");
  }
  if (!(thickness > 0.0) || !std::isfinite(thickness)) {
    throw InvalidInputError("--thickness", "the plate thickness must be a positive number (got " + format_number(thickness) + ")");
  }
  if (side == PlateSide::automatic) throw Error(ExitCode::internal, "ThickPlates: choose the side first (front or back)");
  const Assembly& assembly = design.assembly;
  if (const double resolved = 1e-6 * assembly.model_size(); thickness < resolved) {
    throw InvalidInputError("--thickness", "a plate " + format_human(thickness) + " thick is below what the model "
                                           "resolves (1e-6 of its size, " + format_human(resolved) +
                                           "): such plates are the panels themselves");
  }
  tolerance_ = 1e-9 * assembly.model_size();
  const double s = side == PlateSide::front ? 1.0 : -1.0;
  const Points x0 = positions(assembly.t_star());

  // The plates: every valid panel's distinct corners, its plate direction.
  std::vector<Vec3> plate_direction;
  // Corners that coincide throughout the motion (a boundary column's apex rows) are one corner.
  const std::vector<Quad> welded = welded_faces(mesh_, coincident_vertices(mesh_, assembly));
  for (std::size_t f = 0; f < mesh_.faces.size(); ++f) {
    const Quad& q = mesh_.faces[f];
    const PanelShape shape = panel_shape({x0[q[0]], x0[q[1]], x0[q[2]], x0[q[3]]});
    if (!is_valid_panel(shape)) continue;
    Plate plate;
    plate.face = f;
    plate.corners = distinct_corners(welded[f]);
    if (plate.corners.size() < 3) continue;
    std::vector<Vec3> p;
    for (std::size_t v : plate.corners) p.push_back(x0[v]);
    const Vec3 area = area_vector(p);
    panel_area_ += area.norm();
    plate.bottom = p;  // world at t* for now; moved to the frame below
    plate_direction.push_back(s * area.normalized());
    plates_.push_back(std::move(plate));
  }

  // Hinges: ordered pairs of plates on one edge.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, int>>> edges;
  for (std::size_t k = 0; k < plates_.size(); ++k) {
    const std::vector<std::size_t>& c = plates_[k].corners;
    for (std::size_t e = 0; e < c.size(); ++e) {
      const std::size_t u = c[e], v = c[(e + 1) % c.size()];
      edges[{std::min(u, v), std::max(u, v)}].push_back({k, static_cast<int>(e)});
    }
  }
  neighbours_.assign(plates_.size(), {});
  for (const auto& [edge, on] : edges) {
    for (const auto& [a, ea] : on) {
      for (const auto& [b, eb] : on) {
        if (a == b) continue;
        HingePair h{a, b, ea, eb, false};
        // b's plate lies in the wedge from a (towards a's plate) to b when its
        // direction points back from b's panel into that wedge.
        const double phi = pair_opening(h, x0);
        const Plate& pa = plates_[a];
        const Vec3& m_a = plate_direction[a];
        const Vec3 d_a = (pa.bottom[(ea + 1) % pa.bottom.size()] - pa.bottom[ea]).normalized();
        const Vec3 x_axis = area_vector(pa.bottom).normalized().cross(d_a);  // into a
        const Vec3 inside = std::sin(phi) * x_axis - std::cos(phi) * m_a;
        h.facing = plate_direction[b].dot(inside) > 0.0;
        hinges_.push_back(h);
        if (std::find(neighbours_[a].begin(), neighbours_[a].end(), b) == neighbours_[a].end()) neighbours_[a].push_back(b);
      }
    }
  }

  // Bevel bounds: the smallest plate-side opening of each pair over the range.
  std::vector<double> smallest(hinges_.size(), std::numeric_limits<double>::infinity());
  const std::vector<double> at_star = openings(x0);
  // The floor of a bevel never goes above what t* itself allows.
  for (Plate& p : plates_) p.ceiling.assign(p.corners.size(), quarter_turn);
  for (std::size_t k = 0; k < hinges_.size(); ++k) {
    const HingePair& h = hinges_[k];
    double& ceiling = plates_[h.a].ceiling[h.edge_a];
    ceiling = std::min(ceiling, std::max(0.0, h.facing ? 0.5 * at_star[k] : at_star[k]));
  }
  for (std::size_t k = 0; k < hinges_.size(); ++k) smallest[k] = at_star[k];
  for (const double end : {range.first, range.second}) {
    std::vector<double> previous = at_star;
    constexpr std::size_t samples = 64;
    if (end == assembly.t_star()) continue;
    for (std::size_t i = 1; i <= samples; ++i) {
      const std::vector<double> raw = openings(positions(crowded(assembly.t_star(), end, i, samples)));
      for (std::size_t k = 0; k < raw.size(); ++k) {
        previous[k] = continued(raw[k], previous[k]);
        smallest[k] = std::min(smallest[k], previous[k]);
      }
    }
  }
  for (Plate& p : plates_) {
    p.bevel.assign(p.corners.size(), quarter_turn);
    p.hinge.assign(p.corners.size(), false);
  }
  for (const HingePair& h : hinges_) plates_[h.a].hinge[h.edge_a] = true;
  for (std::size_t k = 0; k < hinges_.size(); ++k) {
    const HingePair& h = hinges_[k];
    const double bound = std::max(0.0, h.facing ? 0.5 * smallest[k] : smallest[k]);
    double& bevel = plates_[h.a].bevel[h.edge_a];
    bevel = std::min(bevel, bound);
  }

  // The plates' solids at t*, then in their frames; `chamfer[c]` (> 0) cuts
  // corner c off, square, through the points that far from it along its edges.
  smallest_bevel_ = quarter_turn;
  std::vector<std::vector<Vec3>> world(plates_.size());
  for (std::size_t k = 0; k < plates_.size(); ++k) world[k] = plates_[k].bottom;
  auto shape = [&](std::size_t k, const std::vector<double>& chamfer) {
    Plate& plate = plates_[k];
    const std::vector<Vec3>& p = world[k];
    const std::size_t n = p.size();
    const Vec3 normal = area_vector(p).normalized();
    const Vec3& m = plate_direction[k];
    // The side planes in order around the plate: each edge's, and a chamfer's
    // before its corner's next edge (square, through the points `chamfer[c]` from
    // the top face's corner along its two edges, so that it cuts the top too).
    std::vector<Vec3> edge_normal(n);
    std::vector<double> edge_offset(n);
    for (std::size_t e = 0; e < n; ++e) {
      const Vec3 d = (p[(e + 1) % n] - p[e]).normalized();
      const Vec3 w = normal.cross(d);  // into the panel
      double depth = 0.0;
      for (const Vec3& q : p) depth = std::max(depth, w.dot(q - p[e]));
      const double floor = std::min(std::atan(thickness / (max_inset_fraction * depth)), plate.ceiling[e]);
      double& bevel = plate.bevel[e];
      bevel = std::max(bevel, floor);
      smallest_bevel_ = std::min(smallest_bevel_, bevel);
      const Vec3 v = std::cos(bevel) * w + std::sin(bevel) * m;  // up the side face, away from the edge
      edge_normal[e] = d.cross(v).normalized();
      // A hinge gap moves the side face into the plate by half the gap (in the panel's plane).
      edge_offset[e] = edge_normal[e].dot(p[e] + (plate.hinge[e] ? 0.5 * hinge_gap : 0.0) * w);
    }
    std::vector<Vec3> plane_normal;
    std::vector<double> plane_offset;
    std::vector<Vec3> at;     // a point of the plane at the panel (the bottom's fallback corner)
    std::vector<Vec3> along;  // the side's direction in the panel
    for (std::size_t e = 0; e < n; ++e) {
      plane_normal.push_back(edge_normal[e]);
      plane_offset.push_back(edge_offset[e]);
      at.push_back(p[e]);
      along.push_back(p[(e + 1) % n] - p[e]);
      const std::size_t c = (e + 1) % n;
      if (chamfer.empty() || !(chamfer[c] > 0.0)) continue;
      Eigen::Matrix3d a;
      a.row(0) = m.transpose();
      a.row(1) = edge_normal[e].transpose();
      a.row(2) = edge_normal[c].transpose();
      const Vec3 top_corner = a.colPivHouseholderQr().solve(Vec3(m.dot(p[c]) + thickness, edge_offset[e], edge_offset[c]));
      if (!top_corner.allFinite()) continue;
      const Vec3 u_next = (p[(c + 1) % n] - p[c]).normalized(), u_back = (p[e] - p[c]).normalized();
      const Vec3 line = (u_next - u_back).normalized();
      // Through the bottom's chamfer line (the panel's corner cut `chamfer[c]` along
      // both edges) and the point that far from the top face's corner: it leans as the bevels do.
      const Vec3 bottom_point = p[c] + chamfer[c] * u_next, top_point = top_corner + chamfer[c] * u_next;
      plane_normal.push_back(line.cross(top_point - bottom_point).normalized());
      plane_offset.push_back(plane_normal.back().dot(bottom_point));
      at.push_back(p[c] + chamfer[c] * u_back);
      along.push_back(line);
    }
    const std::size_t sides = plane_normal.size();
    // Each corner where the bottom (height 0) or top (height T) plane meets the two side faces at it.
    auto corners_at = [&](double height) {
      std::vector<Vec3> out(sides);
      for (std::size_t c = 0; c < sides; ++c) {
        const std::size_t before = (c + sides - 1) % sides;
        Eigen::Matrix3d a;
        a.row(0) = m.transpose();
        a.row(1) = plane_normal[before].transpose();
        a.row(2) = plane_normal[c].transpose();
        const Vec3 b(m.dot(at[c]) + height, plane_offset[before], plane_offset[c]);
        out[c] = a.colPivHouseholderQr().solve(b);
        if (!out[c].allFinite()) out[c] = at[c] + height * m;
      }
      return out;
    };
    std::vector<Vec3> top = corners_at(thickness);
    std::vector<Vec3> bottom = hinge_gap > 0.0 || sides != n ? corners_at(0.0) : p;
    // The top and bottom faces must keep every side's direction and the panel's orientation.
    for (std::size_t e = 0; e < sides; ++e) {
      const std::size_t c = (e + 1) % sides;
      for (const std::vector<Vec3>* face : {&bottom, &top}) {
        const std::vector<Vec3>& f = *face;
        if (!((f[c] - f[e]).dot(along[e]) > 0.0) || !(area_vector(f).dot(normal) > 0.0)) {
          const bool gap = face == &bottom;
          throw InvalidInputError(gap ? "--hinge-gap" : "--thickness",
                                  gap ? "a hinge gap of " + format_human(hinge_gap) + " leaves nothing of " +
                                            describe(panel_id(k), assembly.member_count() > 1) + " (a smaller gap)"
                                      : "a plate " + format_human(thickness) + " thick does not fit on " +
                                            describe(panel_id(k), assembly.member_count() > 1) +
                                            ": its bevelled top face vanishes (a thinner plate, or a wider panel)");
        }
      }
    }
    // The frame at t*, and everything in it.
    const Eigen::Matrix3d r = frame(plate, x0);
    const Vec3 origin = x0[plate.corners[0]];
    plate.panel = p;
    for (Vec3& q : plate.panel) q = r.transpose() * (q - origin);
    for (Vec3& q : bottom) q = r.transpose() * (q - origin);
    for (Vec3& q : top) q = r.transpose() * (q - origin);
    plate.bottom = bottom;
    plate.top = top;
    // Convex pieces: the whole plate, or the two halves of a dart along its inner diagonal.
    std::vector<std::vector<std::size_t>> pieces;
    const std::vector<Vec3>& pc = plate.panel;  // in the frame: its normal is +z
    if (n == 4 && sides == n && panel_shape({pc[0], pc[1], pc[2], pc[3]}) == PanelShape::non_convex) {
      const std::array<double, 4> turns = corner_turns({pc[0], pc[1], pc[2], pc[3]}, Vec3::UnitZ());
      const std::size_t reflex = static_cast<std::size_t>(std::min_element(turns.begin(), turns.end()) - turns.begin());
      pieces = {{reflex, (reflex + 1) % 4, (reflex + 2) % 4}, {(reflex + 2) % 4, (reflex + 3) % 4, reflex}};
    } else {
      std::vector<std::size_t> all(sides);
      for (std::size_t c = 0; c < sides; ++c) all[c] = c;
      pieces = {all};
    }
    double size = 0.0;
    for (const Vec3& q : plate.bottom) size = std::max(size, q.norm());
    plate.pieces.clear();
    for (const std::vector<std::size_t>& corners : pieces) {
      Piece piece;
      for (std::size_t c : corners) piece.points.push_back(plate.bottom[c]);
      for (std::size_t c : corners) piece.points.push_back(plate.top[c]);
      hull_axes(piece.points, 1e-9 * (size + thickness), piece.normals, piece.directions);
      for (const Vec3& q : piece.points) piece.centre += q;
      piece.centre /= static_cast<double>(piece.points.size());
      for (const Vec3& q : piece.points) piece.radius = std::max(piece.radius, (q - piece.centre).norm());
      plate.pieces.push_back(std::move(piece));
    }
  };
  for (std::size_t k = 0; k < plates_.size(); ++k) shape(k, {});

  // Plates that share only a corner (no hinge: plates of two members meeting at
  // a vertex) and overlap there at t*: both cut off square at that corner, by
  // T, 2T, 4T, 8T (at most 0.4 of the shorter edge at it) until they clear;
  // when nothing within that clears them, they stay whole (check names them).
  std::map<std::size_t, std::vector<std::pair<std::size_t, std::size_t>>> at_vertex;  // mesh vertex -> (plate, corner)
  for (std::size_t k = 0; k < plates_.size(); ++k) {
    for (std::size_t c = 0; c < plates_[k].corners.size(); ++c) at_vertex[plates_[k].corners[c]].push_back({k, c});
  }
  std::vector<std::vector<double>> chamfers(plates_.size());
  for (std::size_t k = 0; k < plates_.size(); ++k) chamfers[k].assign(plates_[k].corners.size(), 0.0);
  auto overlap = [&](std::size_t a, std::size_t b) {
    const Eigen::Matrix3d ra = frame(plates_[a], x0), rb = frame(plates_[b], x0);
    const Vec3 oa = x0[plates_[a].corners[0]], ob = x0[plates_[b].corners[0]];
    for (const Piece& pa : plates_[a].pieces) {
      for (const Piece& pb : plates_[b].pieces) {
        if (sat_depth(pa, ra, oa, pb, rb, ob) > tolerance_) return true;
      }
    }
    return false;
  };
  auto shortest_edge_at = [&](std::size_t k, std::size_t c) {
    const std::vector<Vec3>& p = world[k];
    const std::size_t n = p.size();
    return std::min((p[(c + 1) % n] - p[c]).norm(), (p[(c + n - 1) % n] - p[c]).norm());
  };
  corners_trimmed_ = 0;
  for (const auto& [vertex, on] : at_vertex) {
    for (std::size_t i = 0; i < on.size(); ++i) {
      for (std::size_t j = i + 1; j < on.size(); ++j) {
        const auto [a, ca] = on[i];
        const auto [b, cb] = on[j];
        const std::vector<std::size_t>& n = neighbours_[a];
        if (a == b || std::find(n.begin(), n.end(), b) != n.end() || !overlap(a, b)) continue;
        auto dart = [&](std::size_t k) {
          const std::vector<Vec3>& w = world[k];
          return w.size() == 4 && panel_shape({w[0], w[1], w[2], w[3]}) == PanelShape::non_convex;
        };
        if (dart(a) || dart(b)) continue;  // (a cut corner of a dart: not its convex pieces)
        const std::vector<double> was_a = chamfers[a], was_b = chamfers[b];
        bool clear = false;
        for (const double factor : {0.25, 0.5, 1.0, 2.0, 4.0}) {
          const double d = factor * thickness;
          if (d > 0.4 * shortest_edge_at(a, ca) || d > 0.4 * shortest_edge_at(b, cb)) break;
          chamfers[a][ca] = std::max(was_a[ca], d);
          chamfers[b][cb] = std::max(was_b[cb], d);
          try {
            shape(a, chamfers[a]);
            shape(b, chamfers[b]);
          } catch (const InvalidInputError&) {
            break;  // a top face vanished: no deeper cut
          }
          if (!overlap(a, b)) {
            clear = true;
            break;
          }
        }
        if (clear) {
          corners_trimmed_ += 2;
          continue;
        }
        chamfers[a] = was_a;
        chamfers[b] = was_b;
        shape(a, chamfers[a]);
        shape(b, chamfers[b]);
      }
    }
  }
}

PanelId ThickPlates::panel_id(std::size_t k) const { return phedra::panel_id(design_.assembly, mesh_, plates_[k].face); }

Points ThickPlates::positions(double t) const {
  design_.assembly.evaluate(t, configuration_);
  return mesh_.positions(configuration_);
}

Eigen::Matrix3d ThickPlates::frame(const Plate& p, const Points& x) const {
  std::vector<Vec3> c;
  for (std::size_t v : p.corners) c.push_back(x[v]);
  const Vec3 z = area_vector(c).normalized();
  Vec3 along = c[1] - c[0];
  along -= z.dot(along) * z;
  const Vec3 e = along.normalized();
  Eigen::Matrix3d r;
  r.col(0) = e;
  r.col(1) = z.cross(e);
  r.col(2) = z;
  return r;
}

double ThickPlates::pair_opening(const HingePair& h, const Points& x) const {
  const Plate& pa = plates_[h.a];
  const Plate& pb = plates_[h.b];
  const std::size_t na = pa.corners.size(), nb = pb.corners.size();
  std::vector<Vec3> ca, cb;
  for (std::size_t v : pa.corners) ca.push_back(x[v]);
  for (std::size_t v : pb.corners) cb.push_back(x[v]);
  const Vec3 origin = ca[h.edge_a];
  const Vec3 e = (ca[(h.edge_a + 1) % na] - origin).normalized();
  const Vec3 normal_a = area_vector(ca).normalized();
  const Vec3 normal_b = area_vector(cb).normalized();
  const Vec3 m_a = side_ == PlateSide::front ? normal_a : Vec3(-normal_a);
  const Vec3 u_a = normal_a.cross(e);  // into a
  const Vec3 e_b = (cb[(h.edge_b + 1) % nb] - cb[h.edge_b]).normalized();
  const Vec3 u_b = normal_b.cross(e_b);  // into b
  double phi = std::atan2(m_a.dot(u_b), u_a.dot(u_b));
  if (phi < 0.0) phi += full_turn;
  return phi;
}

std::vector<double> ThickPlates::openings(const Points& x) const {
  std::vector<double> out(hinges_.size());
  for (std::size_t k = 0; k < hinges_.size(); ++k) out[k] = pair_opening(hinges_[k], x);
  return out;
}

double ThickPlates::sat_depth(const Piece& a, const Eigen::Matrix3d& ra, const Vec3& oa, const Piece& b,
                              const Eigen::Matrix3d& rb, const Vec3& ob) const {
  // b in a's frame.
  const Eigen::Matrix3d rab = ra.transpose() * rb;
  const Vec3 shift = ra.transpose() * (ob - oa);
  const Vec3 centre_b = rab * b.centre + shift;
  if ((centre_b - a.centre).norm() > a.radius + b.radius + tolerance_) return -1.0;
  thread_local std::vector<Vec3> pb;
  pb.resize(b.points.size());
  for (std::size_t i = 0; i < b.points.size(); ++i) pb[i] = rab * b.points[i] + shift;
  double depth = std::numeric_limits<double>::infinity();
  auto overlap = [&](const Vec3& axis) {
    double a_lo = std::numeric_limits<double>::infinity(), a_hi = -a_lo, b_lo = a_lo, b_hi = -a_lo;
    for (const Vec3& q : a.points) {
      const double d = axis.dot(q);
      a_lo = std::min(a_lo, d);
      a_hi = std::max(a_hi, d);
    }
    for (const Vec3& q : pb) {
      const double d = axis.dot(q);
      b_lo = std::min(b_lo, d);
      b_hi = std::max(b_hi, d);
    }
    depth = std::min(depth, std::min(a_hi, b_hi) - std::max(a_lo, b_lo));
    return depth > tolerance_;
  };
  for (const Vec3& n : a.normals) {
    if (!overlap(n)) return depth;
  }
  for (const Vec3& n : b.normals) {
    if (!overlap(rab * n)) return depth;
  }
  for (const Vec3& da : a.directions) {
    for (const Vec3& d : b.directions) {
      const Vec3 axis = da.cross(rab * d);
      const double length = axis.norm();
      if (length < 1e-9) continue;
      if (!overlap(axis / length)) return depth;
    }
  }
  return depth;
}

std::optional<ThickPlates::Contact> ThickPlates::collision(const Points& x, const std::vector<double>& previous,
                                                           std::vector<double>& next) const {
  const std::vector<double> raw = openings(x);
  next.resize(raw.size());
  std::optional<Contact> first;
  for (std::size_t k = 0; k < raw.size(); ++k) {
    next[k] = continued(raw[k], previous[k]);
    const HingePair& h = hinges_[k];
    const double need = plates_[h.a].bevel[h.edge_a] + (h.facing ? plates_[h.b].bevel[h.edge_b] : 0.0);
    if (!first && next[k] < need - bevel_angle_tolerance) first = Contact{h.a, h.b, true, (need - next[k]) * thickness_};
  }
  if (first) return first;
  // Separate plates: convex pieces, boxes as the broad phase, SAT as the narrow one.
  std::vector<Eigen::Matrix3d> frames(plates_.size());
  std::vector<Vec3> origins(plates_.size());
  std::vector<Box> boxes;
  std::vector<std::pair<std::size_t, std::size_t>> owner;  // (plate, piece)
  for (std::size_t k = 0; k < plates_.size(); ++k) {
    frames[k] = frame(plates_[k], x);
    origins[k] = x[plates_[k].corners[0]];
    for (std::size_t i = 0; i < plates_[k].pieces.size(); ++i) {
      const Piece& piece = plates_[k].pieces[i];
      Box box{Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
      for (const Vec3& q : piece.points) {
        const Vec3 w = frames[k] * q + origins[k];
        box.lo = box.lo.cwiseMin(w);
        box.hi = box.hi.cwiseMax(w);
      }
      box.lo.array() -= tolerance_;
      box.hi.array() += tolerance_;
      boxes.push_back(box);
      owner.push_back({k, i});
    }
  }
  BoxTree(boxes).for_each_pair([&](std::size_t i, std::size_t j) {
    const auto [a, pa] = owner[i];
    const auto [b, pb] = owner[j];
    if (a == b) return true;
    const std::vector<std::size_t>& n = neighbours_[a];
    if (std::find(n.begin(), n.end(), b) != n.end()) return true;
    const double depth = sat_depth(plates_[a].pieces[pa], frames[a], origins[a], plates_[b].pieces[pb], frames[b], origins[b]);
    if (depth > tolerance_) {
      first = Contact{a, b, false, depth};
      return false;
    }
    return true;
  });
  return first;
}

std::vector<Solid> ThickPlates::solids(const Points& x) const {
  std::vector<Solid> out;
  out.reserve(plates_.size());
  for (const Plate& plate : plates_) {
    const Eigen::Matrix3d r = frame(plate, x);
    const Vec3 origin = x[plate.corners[0]];
    const std::size_t n = plate.bottom.size();
    Solid s;
    for (const Vec3& q : plate.bottom) s.vertices.push_back(r * q + origin);
    for (const Vec3& q : plate.top) s.vertices.push_back(r * q + origin);
    // In the frame the panel's normal is +z; the plate lies towards +z (front) or -z (back).
    const bool up = side_ == PlateSide::front;
    // Fan from the reflex corner of a dart (from corner 0 otherwise): inside the polygon either way.
    std::size_t fan = 0;
    if (n == 4) {
      std::vector<Vec3> c(plate.bottom);
      const std::array<double, 4> turns = corner_turns({c[0], c[1], c[2], c[3]}, Vec3::UnitZ());
      fan = static_cast<std::size_t>(std::min_element(turns.begin(), turns.end()) - turns.begin());
      if (turns[fan] >= 0.0) fan = 0;
    }
    auto add = [&](std::size_t i, std::size_t j, std::size_t k, bool keep) {
      if (keep) {
        s.triangles.push_back({i, j, k});
      } else {
        s.triangles.push_back({i, k, j});
      }
    };
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const std::size_t a = fan, b = (fan + i) % n, c = (fan + i + 1) % n;
      add(a, b, c, !up);            // bottom: outward away from the plate
      add(n + a, n + b, n + c, up);  // top
    }
    for (std::size_t e = 0; e < n; ++e) {
      const std::size_t f = (e + 1) % n;
      add(e, f, n + f, up);
      add(e, n + f, n + e, up);
    }
    out.push_back(std::move(s));
  }
  return out;
}

Solid ThickPlates::solid(std::size_t k, double t) const {
  const Points x = positions(t);
  return solids(x)[k];
}

}  // namespace phedra
