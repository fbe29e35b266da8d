#include "phedra/bar_hinge_model.h"

#include "block_assembly.h"

#include "material_calibration.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace phedra {

std::string to_string(PanelModel model) { return model == PanelModel::n4b5 ? "n4b5" : "n5b8"; }

PanelModel parse_panel_model(const std::string& name) {
  if (name == "n4b5") return PanelModel::n4b5;
  if (name == "n5b8") return PanelModel::n5b8;
  throw InvalidInputError("--panels", "unknown panel model \"" + name +
                                          "\" (n4b5: each quad split along its shorter diagonal; n5b8: a centre "
                                          "node and four spokes, MERLIN2's default)");
}

void StiffnessOptions::validate() const {
  auto positive = [](double v, const std::string& option, const std::string& what) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw InvalidInputError(option, "must be a positive number (got " + format_number(v) + "): " + what);
    }
  };
  if (material) {
    if (panels == PanelModel::n4b5) {
      throw InvalidInputError("--material", "the calibration from a material is MERLIN2's for n5b8 panels only; "
                                            "use --panels n5b8, or give --bar, --fold and --bend with n4b5");
    }
    positive(material->youngs_modulus, "--material", "Young's modulus E");
    if (!(material->poisson > 0.0 && material->poisson < 0.5)) {
      throw InvalidInputError("--material", "Poisson's ratio nu must be in (0, 0.5) (at 0 the n5b8 spokes have no area), got " +
                                                format_number(material->poisson));
    }
    positive(material->thickness, "--thickness", "the plate thickness");
    if (material->length_scale) positive(*material->length_scale, "--length-scale", "the length scale L*");
    return;
  }
  positive(bar, "--bar", "the bars' stiffness EA");
  positive(bend, "--bend", "the bending stiffness KB");
  if (fold) positive(*fold, "--fold", "the fold stiffness KF");
}

namespace {

struct EdgeUse {
  std::size_t panel;
  std::size_t from, to;  ///< the edge as it runs in the panel
  std::size_t wing;      ///< the third node of the panel's triangle at the edge
};

std::string panel_name(std::size_t face) { return "panel " + std::to_string(face); }

/// An unordered pair of node indices as one key (hashed: a std::map of 60,000
/// edges took about a third of the model's construction on a 10^4-panel array).
std::uint64_t edge_key(std::size_t a, std::size_t b) {
  const auto [lo, hi] = std::minmax(a, b);
  return (static_cast<std::uint64_t>(lo) << 32) | static_cast<std::uint64_t>(hi);
}

/// A face's sorted corner nodes (a triangle's fourth SIZE_MAX), hashed.
struct CornerSetHash {
  std::size_t operator()(const std::array<std::size_t, 4>& c) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::size_t v : c) h = (h ^ static_cast<std::uint64_t>(v)) * 0xff51afd7ed558ccdull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

}  // namespace

ModelMesh model_mesh(const Design& design, const AssemblyConfiguration& at) {
  ModelMesh out;
  out.t = at.t;
  const AssemblyMesh mesh = panel_mesh(design);
  const Points vertices = mesh.positions(at);
  const std::vector<std::size_t> same = coincident_points({vertices}, 1e-9 * design.assembly.model_size());
  std::vector<std::size_t> node_of_representative(vertices.size(), SIZE_MAX);
  auto node = [&](std::size_t v) {
    std::size_t& n = node_of_representative[same[v]];
    if (n == SIZE_MAX) {
      n = out.node_vertex.size();
      out.node_vertex.push_back(mesh.vertices[same[v]]);
      out.positions.push_back(vertices[same[v]]);
    }
    return n;
  };
  std::unordered_set<std::array<std::size_t, 4>, CornerSetHash> seen;  // sorted node sets
  seen.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    std::array<std::size_t, 4> c{};
    for (int k = 0; k < 4; ++k) c[k] = node(mesh.faces[f][k]);
    std::vector<std::size_t> corners;
    for (int k = 0; k < 4; ++k) {
      if (c[k] != c[(k + 1) % 4]) corners.push_back(c[k]);
    }
    std::vector<std::size_t> key = corners;
    std::sort(key.begin(), key.end());
    const bool distinct = std::adjacent_find(key.begin(), key.end()) == key.end();
    if (corners.size() < 3 || !distinct) {
      const std::size_t nodes = static_cast<std::size_t>(std::unique(key.begin(), key.end()) - key.begin());
      throw InvalidInputError(panel_name(f), "its corners fall on " + std::to_string(nodes) +
                                                 " nodes at t = " + format_number(at.t) +
                                                 (nodes == 3 ? " (two opposite corners meet: not a triangle)" : "") +
                                                 ": the bar-and-hinge model has no panel for it (a degenerate panel)");
    }
    std::array<std::size_t, 4> sorted_key{SIZE_MAX, SIZE_MAX, SIZE_MAX, SIZE_MAX};
    std::copy(key.begin(), key.end(), sorted_key.begin());
    if (!seen.insert(sorted_key).second) {
      ++out.dropped_faces;  // a wall two cells share, modelled once
      continue;
    }
    out.triangle_panels += corners.size() == 3;
    out.panels.push_back({f, corners, std::nullopt, 0, 0.0});
  }
  return out;
}

void ModelMesh::nodes(const std::vector<Points>& members, Points& out) const {
  out.resize(node_vertex.size());
  for (std::size_t n = 0; n < node_vertex.size(); ++n) out[n] = members[node_vertex[n].member][node_vertex[n].vertex];
}

BarHingeModel::BarHingeModel(const Design& design, const AssemblyConfiguration& at, const StiffnessOptions& options)
    : panels_model_(options.panels) {
  options.validate();
  mesh_ = model_mesh(design, at);
  positions_ = mesh_.positions;
  const double size = design.assembly.model_size();
  std::vector<ModelPanel>& panels = mesh_.panels;

  // Bars on the panels' edges, their uses, diagonals or spokes and bending hinges.
  std::unordered_map<std::uint64_t, std::size_t> bar_of;
  bar_of.reserve(3 * panels.size());
  std::vector<std::vector<EdgeUse>> uses;
  auto new_bar = [&](std::size_t a, std::size_t b) {
    bars_.push_back({{a, b}, (positions_[b] - positions_[a]).norm(), options.bar});
    uses.emplace_back();
    return bars_.size() - 1;
  };
  auto bar = [&](std::size_t a, std::size_t b) {
    auto [it, added] = bar_of.emplace(edge_key(a, b), bars_.size());
    if (added) new_bar(a, b);
    return it->second;
  };
  std::vector<Hinge> bends;
  for (std::size_t pi = 0; pi < panels.size(); ++pi) {
    ModelPanel& p = panels[pi];
    const std::vector<std::size_t>& v = p.corners;
    const std::size_t count = v.size();
    std::vector<std::size_t> wing(count);  // the wing of edge k (v[k] -> v[k+1])
    if (count == 3) {
      for (std::size_t k = 0; k < 3; ++k) wing[k] = v[(k + 2) % 3];
    } else {
      const double d02 = (positions_[v[2]] - positions_[v[0]]).norm();
      const double d13 = (positions_[v[3]] - positions_[v[1]]).norm();
      if (options.panels == PanelModel::n4b5) {
        if (!(std::abs(d02 - d13) > 1e-6 * std::max(d02, d13))) {
          throw InvalidInputError(panel_name(p.face), "its diagonals are equal to 1e-6 (|P0-P2| = " +
                                                          format_number(d02) + ", |P1-P3| = " + format_number(d13) +
                                                          "): n4b5 has no shorter one to split it along; use --panels n5b8");
        }
        const bool on02 = d02 < d13;
        const std::size_t a = on02 ? 0 : 1;  // the split v[a] - v[a + 2]
        p.base = a;
        bar(v[a], v[a + 2]);
        // MERLIN2's order: [P0 P2 P1 P3] or [P1 P3 P0 P2].
        bends.push_back({{v[a], v[a + 2], on02 ? v[1] : v[0], on02 ? v[3] : v[2]}, HingeKind::bend,
                         on02 ? d02 : d13, options.bend, {pi, pi}});
        // Edge k holds one end of the split; its triangle's third corner is the other end.
        for (std::size_t k = 0; k < 4; ++k) wing[k] = (k == a || (k + 1) % 4 == a) ? v[a + 2] : v[a];
      } else {
        // MERLIN2's centre: the diagonals' lines meet (least squares), taken on the shorter one.
        const Vec3 m = (positions_[v[2]] - positions_[v[0]]) / d02, n = (positions_[v[3]] - positions_[v[1]]) / d13;
        Eigen::Matrix<double, 3, 2> system;
        system << m, -n;
        const Eigen::Vector2d coefficient = system.colPivHouseholderQr().solve(positions_[v[1]] - positions_[v[0]]);
        const double along02 = coefficient(0) / d02, along13 = coefficient(1) / d13;
        if (!(along02 > 0.0 && along02 < 1.0 && along13 > 0.0 && along13 < 1.0)) {
          throw InvalidInputError(panel_name(p.face),
                                  "it is not convex at t = " + format_number(at.t) + ": its diagonals' lines meet " +
                                      format_number(along02) + " of the way along P0-P2 and " + format_number(along13) +
                                      " along P1-P3, outside the panel, where n5b8 would put its centre node; use "
                                      "--panels n4b5 (its triangles need no centre)");
        }
        p.base = d02 < d13 ? 0 : 1;
        p.ratio = d02 < d13 ? along02 : along13;
        const Vec3 centre = positions_[v[p.base]] + p.ratio * (positions_[v[p.base + 2]] - positions_[v[p.base]]);
        p.centre = positions_.size();
        positions_.push_back(centre);
        for (std::size_t k = 0; k < 4; ++k) {
          const std::size_t b = new_bar(*p.centre, v[k]);  // the centre is a new node: no other bar has it
          bends.push_back({{*p.centre, v[k], v[(k + 3) % 4], v[(k + 1) % 4]}, HingeKind::bend, bars_[b].length,
                           options.bend, {pi, pi}});
          wing[k] = *p.centre;
        }
      }
    }
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t b = bar(v[k], v[(k + 1) % count]);
      uses[b].push_back({pi, v[k], v[(k + 1) % count], wing[k]});
    }
  }
  // A fold hinge for every pair of panels at an edge; the edge runs as in the first panel.
  for (std::size_t b = 0; b < bars_.size(); ++b) {
    const std::vector<EdgeUse>& u = uses[b];
    for (std::size_t x = 0; x < u.size(); ++x) {
      for (std::size_t y = x + 1; y < u.size(); ++y) {
        hinges_.push_back({{u[x].from, u[x].to, u[x].wing, u[y].wing}, HingeKind::fold, bars_[b].length,
                           options.fold_value(), {u[x].panel, u[y].panel}});
      }
    }
  }
  folds_ = hinges_.size();
  hinges_.insert(hinges_.end(), bends.begin(), bends.end());
  for (const Hinge& h : hinges_) {
    const HingeNodes x = hinge_nodes(h, positions_);
    const double axis = (x.k - x.j).norm();
    const double wings = std::min((x.i - x.j).cross(x.k - x.j).norm(), (x.k - x.j).cross(x.k - x.l).norm());
    if (!(wings > 1e-12 * axis * size)) {
      throw InvalidInputError(panel_name(panels[h.panels[0]].face),
                              "a triangle of the model at t = " + format_number(at.t) +
                                  " has no area (a wing on its hinge's axis): the hinge's angle is undefined");
    }
  }
  if (options.material) calibrate_from_material(*options.material, panels, positions_, bars_, hinges_);
  check_stiffness_spread(options);
}

void BarHingeModel::check_stiffness_spread(const StiffnessOptions& options) const {
  // Bars (EA) and hinges (k per unit length) have the same units; K's smallest
  // eigenvalues cannot be told from rounding when they span more than this, and
  // beyond 1e100 (or under 1e-100) its entries overflow (or vanish).
  constexpr double spread = 1e12, extreme = 1e100;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const Bar& b : bars_) lo = std::min(lo, b.stiffness), hi = std::max(hi, b.stiffness);
  for (const Hinge& h : hinges_) lo = std::min(lo, h.stiffness), hi = std::max(hi, h.stiffness);
  if (hi == 0.0) return;
  if (hi / lo <= spread && hi <= extreme && lo >= 1.0 / extreme) return;
  const std::string range = "the bars' and hinges' stiffnesses span " + format_human(lo) + " to " + format_human(hi);
  if (options.material) {
    throw InvalidInputError("--thickness", range + " with this plate thickness (" +
                                               format_human(options.material->thickness) +
                                               "): they must lie within 1e12 of each other (a plate between about "
                                               "1e-6 and 1 times the model size) and between 1e-100 and 1e100");
  }
  throw InvalidInputError("--bar", range + " (--bar " + format_human(options.bar) + ", --fold " +
                                       format_human(options.fold_value()) + ", --bend " + format_human(options.bend) +
                                       "): they must lie within 1e12 of each other, and between 1e-100 and 1e100");
}

void BarHingeModel::place_centres(Points& out) const {
  out.resize(positions_.size());
  for (const ModelPanel& p : mesh_.panels) {
    if (!p.centre) continue;
    const Vec3& a = out[p.corners[p.base]];
    out[*p.centre] = a + p.ratio * (out[p.corners[p.base + 2]] - a);
  }
}

void BarHingeModel::node_positions(const AssemblyConfiguration& c, Points& out) const {
  mesh_.nodes(c.members, out);
  place_centres(out);
}

void BarHingeModel::node_rates(const std::vector<Points>& member_rates, Points& out) const {
  mesh_.nodes(member_rates, out);
  place_centres(out);
}

std::vector<std::array<std::uint32_t, 3>> BarHingeModel::triangles() const {
  std::vector<std::array<std::uint32_t, 3>> out;
  auto add = [&](std::size_t a, std::size_t b, std::size_t c) {
    out.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(c)});
  };
  for (const ModelPanel& p : mesh_.panels) {
    const std::vector<std::size_t>& v = p.corners;
    if (v.size() == 3) {
      add(v[0], v[1], v[2]);
    } else if (p.centre) {
      for (std::size_t k = 0; k < 4; ++k) add(*p.centre, v[k], v[(k + 1) % 4]);
    } else {
      const std::size_t a = p.base;
      add(v[a], v[a + 1], v[a + 2]);
      add(v[a + 2], v[(a + 3) % 4], v[a]);
    }
  }
  return out;
}

double BarHingeModel::angle(std::size_t h, const Points& x) const { return hinge_angle(hinge_nodes(hinges_[h], x)); }

Eigen::SparseMatrix<double> BarHingeModel::stiffness() const {
  return stiffness_upper().selfadjointView<Eigen::Upper>();
}

Eigen::SparseMatrix<double> BarHingeModel::stiffness_upper() const {
  std::vector<std::span<const std::size_t>> elements;
  elements.reserve(bars_.size() + hinges_.size());
  for (const Bar& b : bars_) elements.emplace_back(b.nodes);
  for (const Hinge& h : hinges_) elements.emplace_back(h.nodes);
  BlockAssembly k(positions_.size(), elements);
  for (const Bar& b : bars_) {
    const Vec3 e = (positions_[b.nodes[1]] - positions_[b.nodes[0]]) / b.length;
    const Mat3 block = (b.stiffness / b.length) * (e * e.transpose());
    const auto [low, high] = std::minmax(b.nodes[0], b.nodes[1]);
    k.add(b.nodes[0], b.nodes[0], block);
    k.add(b.nodes[1], b.nodes[1], block);
    k.add(low, high, -block);
  }
  for (const Hinge& h : hinges_) {
    const std::array<Vec3, 4> g = hinge_angle_gradient(hinge_nodes(h, positions_));
    const double stiffness = h.stiffness * h.length;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        if (h.nodes[r] <= h.nodes[c]) k.add(h.nodes[r], h.nodes[c], stiffness * (g[r] * g[c].transpose()));
      }
    }
  }
  return k.upper();
}

}  // namespace phedra
