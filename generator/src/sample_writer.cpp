#include "phedra/sample_writer.h"

#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace phedra {
namespace {

void append_finite(std::string& out, double x, const char* what) {
  if (!std::isfinite(x)) throw Error(ExitCode::internal, std::string("refusing to write a non-finite ") + what);
  append_number(out, x);
}

void append_index_list(std::string& out, const std::size_t* values, std::size_t count) {
  out += '[';
  for (std::size_t k = 0; k < count; ++k) {
    if (k) out += ',';
    out += std::to_string(values[k]);
  }
  out += ']';
}

}  // namespace

std::string sample_json(const PHedron& p, const std::vector<double>& ts) {
  const GridTopology& g = p.topology();
  std::string out;
  out.reserve(64 * g.vertex_count() * (ts.size() + 1));
  out += "{\"name\":" + nlohmann::json(p.input().name).dump();
  out += ",\"t_star\":";
  append_finite(out, p.t_star(), "t_star");
  out += ",\"case\":\"";
  out += to_string(p.motion_case());
  out += "\",\"flexion_interval\":[";
  append_finite(out, p.flexion_interval().lower.t, "t_lambda");
  out += ',';
  append_finite(out, p.flexion_interval().upper.t, "t_mu");
  out += "],\n\"labels\":[";
  for (std::size_t v = 0; v < g.vertex_count(); ++v) {
    if (v) out += ',';
    const std::size_t label[2] = {g.row_of(v), g.column_of(v)};
    append_index_list(out, label, 2);
  }
  out += "],\n\"faces\":[";
  for (std::size_t f = 0; f < g.faces().size(); ++f) {
    if (f) out += ',';
    append_index_list(out, g.faces()[f].data(), 4);
  }
  out += "],\n\"samples\":[";
  Points vertices(g.vertex_count());
  for (std::size_t k = 0; k < ts.size(); ++k) {
    p.evaluate(ts[k], vertices);
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

}  // namespace phedra
