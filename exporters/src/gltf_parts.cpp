#include "gltf_parts.h"

#include "phedra/errors.h"

namespace phedra::gltf {

float checked(double x) {
  const float f = static_cast<float>(x);
  if (!std::isfinite(f)) throw Error(ExitCode::internal, "refusing to write a non-finite number to glTF");
  return f;
}

std::string face_name(const Assembly& a, const AssemblyMesh& mesh, std::size_t f) {
  const VertexRef& r = mesh.vertices[mesh.faces[f][0]];
  const GridTopology& g = a.topology(mesh.face_member[f]);
  return a.member_name(mesh.face_member[f]) + " panel (" + std::to_string(g.row_of(r.vertex)) + "," +
         std::to_string(g.column_of(r.vertex)) + ")";
}

}  // namespace phedra::gltf
