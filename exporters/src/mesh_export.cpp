#include "phedra/mesh_export.h"

#include "phedra/assembly_mesh.h"
#include "phedra/errors.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cmath>
#include <sstream>

namespace phedra {

namespace {

struct DoublePrecision : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};

}  // namespace

std::string mesh_text(const Design& design, double t, const std::string& extension, const std::string& comment) {
  using Mesh = OpenMesh::PolyMesh_ArrayKernelT<DoublePrecision>;
  // OpenMesh reports on std::cerr; phedra's own messages say what happened.
  omlog().disable();
  omout().disable();
  omerr().disable();  // a shared wall's refused add_face is expected: it is added again below
  const Assembly& a = design.assembly;
  const AssemblyMesh mesh = panel_mesh(design);
  const Points positions = mesh.positions(a.evaluate(t));
  // Vertices that coincide over the whole motion are one vertex (the later
  // copies are not written), and such a panel is the triangle it is: no edge of
  // zero length.
  const std::vector<std::size_t> representative = coincident_vertices(mesh, a);
  Mesh out;
  std::vector<Mesh::VertexHandle> handles(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (representative[v] != v) continue;
    const Vec3& p = positions[v];
    if (!p.allFinite()) throw Error(ExitCode::internal, "refusing to write a non-finite vertex");
    handles[v] = out.add_vertex(Mesh::Point(p.x(), p.y(), p.z()));
  }
  for (const Quad& q : welded_faces(mesh, representative)) {
    std::vector<Mesh::VertexHandle> face;
    for (std::size_t c : distinct_corners(q)) face.push_back(handles[c]);
    if (out.add_face(face).is_valid()) continue;
    // A wall two cells share makes its hinges non-manifold (three panels on an
    // edge): the panel gets its own copies of its corners, at the same places,
    // so that panel k stays face k of the file.
    for (Mesh::VertexHandle& h : face) {
      const Mesh::Point corner = out.point(h);  // (add_vertex may move the points)
      h = out.add_vertex(corner);
    }
    if (!out.add_face(face).is_valid()) throw Error(ExitCode::internal, "OpenMesh refused a panel");
  }
  std::ostringstream stream;
  OpenMesh::IO::Options options;
  if (!OpenMesh::IO::write_mesh(out, stream, extension, options, 9)) {  // float round trip
    throw Error(ExitCode::internal, "OpenMesh could not write " + extension);
  }
  std::string text = stream.str();
  if (comment.empty()) return text;
  std::string line = comment;
  for (char& c : line) c = c == '\n' || c == '\r' ? ' ' : c;
  if (extension == ".obj") return "# " + line + "\n" + text;
  // PLY: comments follow the format line of the header.
  const std::size_t format = text.find("\nformat ");
  const std::size_t end = format == std::string::npos ? std::string::npos : text.find('\n', format + 1);
  if (end == std::string::npos) return text;
  return text.substr(0, end + 1) + "comment " + line + "\n" + text.substr(end + 1);
}

}  // namespace phedra
