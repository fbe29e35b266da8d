#include "phedra/motion_document.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/phedron.h"

#include <memory>

#include <cmath>
#include <nlohmann/json.hpp>

namespace phedra {
namespace {

void append_finite(std::string& out, double x, const char* what) {
  if (!std::isfinite(x)) throw Error(ExitCode::internal, std::string("refusing to write a non-finite ") + what);
  append_number(out, x);
}

template <class Range>
void append_indices(std::string& out, const Range& values) {
  out += '[';
  bool first = true;
  for (std::size_t v : values) {
    if (!first) out += ',';
    first = false;
    out += std::to_string(v);
  }
  out += ']';
}

template <class Range>
void append_index_lists(std::string& out, const char* key, const Range& lists) {
  out += ",\n\"";
  out += key;
  out += "\":[";
  bool first = true;
  for (const auto& list : lists) {
    if (!first) out += ',';
    first = false;
    append_indices(out, list);
  }
  out += ']';
}

}  // namespace

MotionDocument motion_document(const PHedron& p) {
  MotionDocument d;
  d.name = p.input().name;
  d.kind = p.closed() ? "tube" : "open P-hedron";
  d.t_star = p.t_star();
  d.motion_case = to_string(p.motion_case());
  d.t_lambda = p.flexion_interval().lower.t;
  d.t_mu = p.flexion_interval().upper.t;
  const GridTopology& g = p.topology();
  for (std::size_t v = 0; v < g.vertex_count(); ++v) d.labels.push_back({g.row_of(v), g.column_of(v)});
  d.faces = g.faces();
  d.positions = [&p](double t, Points& out) {
    out.resize(p.vertex_count());
    p.evaluate(t, out);
  };
  return d;
}

std::string motion_json(const MotionDocument& d, const std::vector<double>& ts) {
  std::string out;
  out.reserve(64 * d.labels.size() * (ts.size() + 1));
  out += "{\"name\":" + nlohmann::json(d.name).dump();
  out += ",\"kind\":" + nlohmann::json(d.kind).dump();
  out += ",\"t_star\":";
  append_finite(out, d.t_star, "t_star");
  out += ",\"case\":\"" + d.motion_case + "\",\"flexion_interval\":[";
  append_finite(out, d.t_lambda, "t_lambda");
  out += ',';
  append_finite(out, d.t_mu, "t_mu");
  out += ']';
  if (!d.members.empty()) out += ",\n\"members\":" + nlohmann::json(d.members).dump();
  append_index_lists(out, "labels", d.labels);
  append_index_lists(out, "faces", d.faces);
  if (!d.face_members.empty()) {
    out += ",\n\"face_members\":";
    append_indices(out, d.face_members);
  }
  if (!d.buildability.is_null()) out += ",\n\"buildability\":" + d.buildability.dump();
  out += ",\n\"samples\":[";
  Points vertices;
  for (std::size_t k = 0; k < ts.size(); ++k) {
    d.positions(ts[k], vertices);
    out += k ? ",\n{\"t\":" : "\n{\"t\":";
    append_finite(out, ts[k], "t");
    out += ",\"vertices\":[";
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      out += v ? ",[" : "[";
      for (int c = 0; c < 3; ++c) {
        if (c) out += ',';
        append_finite(out, vertices[v][c], "vertex coordinate");
      }
      out += ']';
    }
    out += "]}";
  }
  out += "]}\n";
  return out;
}

MotionDocument motion_document(const Design& design) {
  const Assembly& a = design.assembly;
  if (a.member_count() == 1) {
    MotionDocument d = motion_document(a.base());
    d.kind = design.kind;
    return d;
  }
  MotionDocument d;
  d.name = a.name();
  d.kind = design.kind;
  d.t_star = a.t_star();
  d.motion_case = to_string(a.base().motion_case());
  d.t_lambda = a.flexion_interval().lower.t;
  d.t_mu = a.flexion_interval().upper.t;
  for (std::size_t m = 0; m < a.member_count(); ++m) d.members.push_back(a.member_name(m));
  auto mesh = std::make_shared<AssemblyMesh>(panel_mesh(design));
  for (const VertexRef& r : mesh->vertices) {
    const GridTopology& g = a.topology(r.member);
    d.labels.push_back({r.member, g.row_of(r.vertex), g.column_of(r.vertex)});
  }
  d.faces = mesh->faces;
  d.face_members = mesh->face_member;
  d.positions = [&a, mesh](double t, Points& out) { out = mesh->positions(a.evaluate(t)); };
  return d;
}

}  // namespace phedra
