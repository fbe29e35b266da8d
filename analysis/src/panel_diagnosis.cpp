#include "phedra/panel_diagnosis.h"

#include "phedra/field_hints.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace phedra {
namespace {

int sign_of(double x) { return x < 0.0 ? -1 : 1; }

/// "V_{3,1} V_{3,2}": vertices named by profile and net column (a tube's column n - 1 is its column 0).
std::string vertex(std::size_t row, std::size_t column) {
  return "V_{" + std::to_string(row) + "," + std::to_string(column) + "}";
}

std::size_t wrap(const PanelNets& p, const Assembly& a, std::size_t member, std::size_t column) {
  return a.closed(member) && column + 1 >= p.net_columns ? column - (p.net_columns - 1) : column;
}

std::string apex(std::size_t k) { return "S_" + std::to_string(k); }

/// The edge k of a face (corner k to k + 1) in net terms.
std::string edge_name(const PanelNets& p, const Assembly& a, std::size_t member, int k) {
  const std::size_t i = p.row, j = p.column, j1 = wrap(p, a, member, j + 1);
  switch (k) {
    case 0: return "profile edge " + vertex(i, j) + " " + vertex(i, j1);
    case 1: return "transversal edge " + vertex(i, j1) + " " + vertex(i + 1, j1);
    case 2: return "profile edge " + vertex(i + 1, j) + " " + vertex(i + 1, j1);
    default: return "transversal edge " + vertex(i, j) + " " + vertex(i + 1, j);
  }
}

std::string why_axial_crossed(const PanelNets& p, const Assembly& a, std::size_t member) {
  const NetState& s = a.reference_state(member);
  const std::vector<double> z = a.apex_heights(member);  // user frame
  const std::size_t i = p.row, j = p.column, n = p.net_columns;
  const Vec3 centre(0.0, 0.0, s.apexes[j + 1]);
  auto ratio = [&](std::size_t row) {
    const Vec3 from = s.axial[row * n + j] - centre, to = s.axial[row * n + j + 1] - centre;
    return from.squaredNorm() > 0.0 ? to.dot(from) / from.squaredNorm() : 0.0;
  };
  const double ra = ratio(i), rb = ratio(i + 1);
  const Sign sign = a.signs(member)[j];
  const std::string centre_name = apex(j + 1);
  const std::string sign_text = std::string("sign '") + (sign == Sign::plus ? "+" : "-") + "' at " + centre_name;
  std::string s_text = "its face in the axial net is crossed";
  if (ra < 0.0 && rb < 0.0) {
    s_text += ": there the profile edges of column " + std::to_string(j) + " pass through the apex " + centre_name +
              " in profiles " + std::to_string(i) + " and " + std::to_string(i + 1) + " (ratios " + format_short(ra) +
              ", " + format_short(rb) + "), so the face is an hourglass about it";
    if (sign == Sign::plus) {
      s_text += "; with " + sign_text + " this happens in every profile because the height of " + centre_name + " (" +
                format_short(z[j + 1]) + ") lies between those of " + apex(j) + " (" + format_short(z[j]) + ") and " +
                apex(j + 2) + " (" + format_short(z[j + 2]) + "): make it the highest or the lowest of the three";
    } else {
      const double vanishing = 0.5 * (z[j] + z[j + 1]);
      s_text += "; with " + sign_text + " the ratio is negative while the axial vertex of column " + std::to_string(j) +
                " lies on the far side of the vanishing height (" + apex(j) + " + " + centre_name + ")/2 = " +
                format_short(vanishing);
    }
  } else if (ra > 0.0 && rb > 0.0 && (ra - 1.0) * (rb - 1.0) < 0.0) {
    s_text += ": the profile edge of column " + std::to_string(j) + " grows away from the apex " + centre_name +
              " in one profile and shrinks towards it in the other (ratios " + format_short(ra) + ", " +
              format_short(rb) + "), so the face's transversal edges cross";
    if (sign == Sign::minus) {
      const double fixed = 0.5 * (z[j] + z[j + 2]);
      const double ha = a.base().frame().height_to_user(s.axial[i * n + j].z());
      const double hb = a.base().frame().height_to_user(s.axial[(i + 1) * n + j].z());
      s_text += "; with " + sign_text + " that happens where the axial vertices " + vertex(i, j) + " (height " +
                format_short(ha) + ") and " + vertex(i + 1, j) + " (" + format_short(hb) +
                ") lie on opposite sides of the height (" + apex(j) + " + " + apex(j + 2) + ")/2 = " +
                format_short(fixed) + ", which the collineation keeps fixed";
    }
  }
  return s_text;
}

std::string why_edge_reversed(const PanelNets& p, const ShapeRule& r, const Assembly& a, std::size_t member) {
  const int k = r.odd_edge;
  std::string s = "its " + edge_name(p, a, member, k) + " has scale " + format_short(r.scales[k]) +
                  " in the parallel net (its length over the axial net's, signed) while the panel's other edges "
                  "have the other sign";
  const bool profile = k == 0 || k == 2;
  if (profile) {
    s += ": the profile edges of column " + std::to_string(p.column) + " point opposite ways in profiles " +
         std::to_string(p.row) + " and " + std::to_string(p.row + 1) +
         " relative to the axial net (one of them shrank through zero)";
  } else {
    const std::size_t c = wrap(p, a, member, p.column + 1);
    s += ": the transversal edges of columns " + std::to_string(p.column) + " and " + std::to_string(c) +
         " between profiles " + std::to_string(p.row) + " and " + std::to_string(p.row + 1) +
         " point opposite ways relative to the axial net";
    const std::size_t column = k == 3 ? p.column : c;
    if (member == 0 && column == 0) {
      s += " (column 0 is the trajectory: the segment trajectory[" + std::to_string(p.row) + "] -> trajectory[" +
           std::to_string(p.row + 1) + "] points against the axial trajectory)";
    }
  }
  return s;
}

std::string why_boundary(const PanelNets& p, const ShapeRule& r, std::size_t member) {
  const double q = r.scales[p.column == 0 ? 1 : 3];
  std::string s = "a boundary-column face: its transversal edge " + vertex(p.row, p.column) + " " +
                  vertex(p.row + 1, p.column) + " is " + format_short(q) +
                  " times the axial net's; between 0 and 1 that makes its boundary edge (" + format_short(q - 1.0) +
                  " times it) run the same way, so the face crosses";
  if (member == 0 && p.column == 0) {
    const double axial = (p.axial[2] - p.axial[1]).norm();
    s += ": the trajectory segment trajectory[" + std::to_string(p.row) + "] -> trajectory[" +
         std::to_string(p.row + 1) + "] (length " + format_short((p.general[2] - p.general[1]).norm()) +
         ") is shorter than in the axial net (" + format_short(axial) + "); longer than that, the face is convex";
  }
  return s;
}

}  // namespace

std::string to_string(PanelCause cause) {
  switch (cause) {
    case PanelCause::none: return "none";
    case PanelCause::axial_face_crossed: return "axial face crossed";
    case PanelCause::edge_reversed: return "edge scale reversed";
    case PanelCause::boundary_segment_short: return "boundary edge scale in (0, 1)";
    case PanelCause::degenerate: return "degenerate";
    case PanelCause::oversized: return "oversized";
    case PanelCause::sliver: return "sliver";
  }
  return "?";
}

std::string format_short(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

ShapeRule apply_shape_rule(const PanelNets& p) {
  ShapeRule r;
  if (p.boundary) {
    // The transversal edge of G is q times A's; the boundary edge is (q - 1) times
    // the same vector: parallel sides, crossed when they run the same way.
    const int e = p.column == 0 ? 1 : 3;
    const double q = edge_scale(p.general[(e + 1) % 4] - p.general[e], p.axial[(e + 1) % 4] - p.axial[e]);
    r.scales[e] = q;
    r.scales[(e + 2) % 4] = q - 1.0;
    r.axial = PanelShape::convex;
    r.predicted = q > 0.0 && q < 1.0 ? PanelShape::bow_tie : PanelShape::convex;
    if (r.predicted == PanelShape::bow_tie) r.cause = PanelCause::boundary_segment_short;
    return r;
  }
  const Vec3 normal = quad_normal(p.axial);
  const std::array<double, 4> turns = corner_turns(p.axial, normal);
  const double straight = 1e-12 * longest_edge_squared(p.axial);
  r.axial = shape_from_turns(turns, straight, straight);
  for (int k = 0; k < 4; ++k) {
    r.scales[k] = edge_scale(p.general[(k + 1) % 4] - p.general[k], p.axial[(k + 1) % 4] - p.axial[k]);
  }
  std::array<double, 4> predicted{};
  int negative_scales = 0;
  for (int k = 0; k < 4; ++k) {
    predicted[k] = sign_of(r.scales[(k + 3) % 4]) * sign_of(r.scales[k]) * turns[k];
    negative_scales += r.scales[k] < 0.0 ? 1 : 0;
  }
  r.predicted = shape_from_turns(predicted, straight, straight);
  if (r.axial == PanelShape::degenerate || r.predicted == PanelShape::degenerate) {
    r.cause = PanelCause::degenerate;
  } else if (r.predicted == PanelShape::bow_tie) {
    if (r.axial == PanelShape::bow_tie) {
      r.cause = PanelCause::axial_face_crossed;
    } else {
      r.cause = PanelCause::edge_reversed;
      const bool odd_is_negative = negative_scales == 1;
      for (int k = 0; k < 4; ++k) {
        if ((r.scales[k] < 0.0) == odd_is_negative) r.odd_edge = k;
      }
      if (negative_scales % 2 == 0) r.odd_edge = -1;  // cannot turn a simple face into a bow-tie (section 9)
    }
  }
  return r;
}

double shape_margin(const PanelNets& p) {
  if (p.boundary) {
    const int e = p.column == 0 ? 1 : 3;
    const double q = edge_scale(p.general[(e + 1) % 4] - p.general[e], p.axial[(e + 1) % 4] - p.axial[e]);
    if (std::abs(q - 1.0) <= 1e-12) return 1.0;  // strip 0: a triangle with the apex
    if (q >= 1.0) return q - 1.0;
    if (q <= 0.0) return -q;
    return -std::min(q, 1.0 - q);
  }
  const Vec3 normal = quad_normal(p.axial);
  std::array<double, 4> g{}, sigma{};
  double largest = 0.0;
  for (int k = 0; k < 4; ++k) {
    sigma[k] = edge_scale(p.general[(k + 1) % 4] - p.general[k], p.axial[(k + 1) % 4] - p.axial[k]);
    largest = std::max(largest, std::abs(sigma[k]));
  }
  if (!(largest > 0.0)) return -1.0;
  double collapse = 1.0;  // an edge shrinking to a point turns two corners at once
  for (int k = 0; k < 4; ++k) collapse = std::min(collapse, std::abs(sigma[k]) / largest);
  if (collapse < 1e-9) return collapse;  // a triangle: on the edge of crossing
  int negative = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 in = p.axial[k] - p.axial[(k + 3) % 4], out = p.axial[(k + 1) % 4] - p.axial[k];
    const double lengths = in.norm() * out.norm();
    const double sine = lengths > 0.0 ? normal.dot(in.cross(out)) / lengths : 0.0;
    g[k] = sign_of(sigma[(k + 3) % 4]) * sign_of(sigma[k]) * sine;
    negative += g[k] < 0.0 ? 1 : 0;
  }
  std::array<double, 4> size{};
  for (int k = 0; k < 4; ++k) size[k] = std::abs(g[k]);
  // A bow-tie becomes simple when one corner turns over, or through a triangle
  // (an edge scale through zero): continuous across both.
  if (negative == 2) return -std::min(*std::min_element(size.begin(), size.end()), collapse);
  double margin = 0.0;
  if (negative == 0 || negative == 4) {
    std::sort(size.begin(), size.end());
    margin = size[1];  // a convex panel crosses only after two corners flip
  } else {
    const bool majority_positive = negative == 1;
    margin = 1.0;
    for (int k = 0; k < 4; ++k) {
      if ((g[k] > 0.0) == majority_positive) margin = std::min(margin, size[k]);
    }
  }
  return std::min(margin, collapse);
}

std::vector<PanelDiagnosis> diagnose_panels(const Design& design, const AssemblyMesh& mesh, const nlohmann::json* preset,
                                            const DiagnosisOptions& options) {
  const Assembly& a = design.assembly;
  const SizeBounds& bounds = options.size;
  const std::vector<PanelShape> shapes = bounded_panel_shapes(a, mesh, bounds);
  AssemblyConfiguration at_star;
  a.evaluate(a.t_star(), at_star);
  const std::vector<PanelProportions> proportions = panel_proportions(mesh.positions(at_star), mesh.faces);
  std::vector<PanelDiagnosis> out;
  std::vector<HintGoal> goals;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const PanelShape shape = shapes[f];
    if (is_valid_panel(shape)) continue;
    const std::size_t m = mesh.face_member[f], local = mesh.face_local[f];
    const std::size_t columns = a.topology(m).face_columns();
    PanelDiagnosis d;
    d.panel = f;
    d.member = m;
    d.strip = local / columns;
    d.column = local % columns;
    d.shared_with = mesh.face_shared_with[f];
    d.shape = shape;
    const PanelNets nets = panel_nets(a, m, local);
    d.rule = apply_shape_rule(nets);
    if (shape == PanelShape::degenerate) d.rule.cause = PanelCause::degenerate;
    if (shape == PanelShape::oversized) d.rule.cause = PanelCause::oversized;
    if (shape == PanelShape::sliver) d.rule.cause = PanelCause::sliver;
    const PanelProportions& size = proportions[f];
    HintGoal goal;
    switch (d.rule.cause) {
      case PanelCause::axial_face_crossed: d.why = why_axial_crossed(nets, a, m); break;
      case PanelCause::boundary_segment_short: d.why = why_boundary(nets, d.rule, m); break;
      case PanelCause::edge_reversed:
        d.why = d.rule.odd_edge >= 0 ? why_edge_reversed(nets, d.rule, a, m)
                                     : "two of its edge scales in the parallel net have the other sign than the axial net's";
        break;
      case PanelCause::degenerate:
        d.why = "it has no area: its corners are collinear" +
                std::string(d.rule.axial == PanelShape::degenerate ? " (already in the axial net)" : "");
        break;
      case PanelCause::oversized:
        d.why = "its " + edge_name(nets, a, m, size.longest) + " is " + format_short(size.longest_edge) + " long, " +
                format_short(size.edge_ratio) + " times the median panel's longest edge (at most " +
                format_short(bounds.max_edge_ratio) + "): lines that meet there are nearly parallel";
        goal = {HintGoal::Kind::edge, size.longest, size.longest_edge / size.edge_ratio * bounds.max_edge_ratio};
        break;
      case PanelCause::sliver:
        d.why = "it is a sliver: its area is " + format_short(size.aspect) + " of its longest edge squared (at least " +
                format_short(bounds.min_aspect) + "): a strip too thin to cut";
        goal = {HintGoal::Kind::aspect, size.longest, bounds.min_aspect};
        break;
      case PanelCause::none:
        // The rule and the geometry disagree only within rounding of a straight corner.
        d.why = "a corner is (numerically) straight: the panel is on the edge of crossing";
        break;
    }
    out.push_back(std::move(d));
    goals.push_back(goal);
  }
  if (preset && options.hints && !out.empty()) {
    std::vector<MemberFace> faces;
    const std::size_t count = std::min(out.size(), options.max_hinted_panels);
    for (std::size_t k = 0; k < count; ++k) faces.push_back({mesh.face_member[out[k].panel], mesh.face_local[out[k].panel]});
    goals.resize(count);
    const std::vector<std::vector<FieldHint>> hints = field_hints(*preset, design, faces, goals);
    for (std::size_t k = 0; k < count; ++k) out[k].hints = hints[k];
  }
  return out;
}

std::string describe(const FieldHint& hint) {
  return std::string(hint.change > 0.0 ? "increase " : "decrease ") + hint.field + " (now " + format_short(hint.value) +
         ") by more than about " + format_short(std::abs(hint.change));
}

}  // namespace phedra
