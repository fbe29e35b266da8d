#include "phedra/solid_export.h"

#include "phedra/errors.h"
#include "phedra/xml_text.h"

#include <zlib.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace phedra {
namespace {

void require_finite(const std::vector<Solid>& solids) {
  for (const Solid& s : solids) {
    for (const Vec3& v : s.vertices) {
      if (!v.allFinite()) throw Error(ExitCode::internal, "a plate vertex is not a finite number; nothing written");
    }
  }
}

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little-endian hosts (x86, WebAssembly)
  out.append(bytes, sizeof(T));
}

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

std::string stl(const std::vector<Solid>& solids, const std::string& comment) {
  std::string out;
  std::string header = ("phedra plates " + comment).substr(0, 80);
  if (header.rfind("solid", 0) == 0) header[0] = 'S';  // a binary STL must not start with "solid"
  header.resize(80, ' ');
  out += header;
  std::uint32_t count = 0;
  for (const Solid& s : solids) count += static_cast<std::uint32_t>(s.triangles.size());
  put(out, count);
  for (const Solid& s : solids) {
    for (const auto& t : s.triangles) {
      const Vec3& a = s.vertices[t[0]];
      const Vec3& b = s.vertices[t[1]];
      const Vec3& c = s.vertices[t[2]];
      Vec3 n = (b - a).cross(c - a);
      if (n.norm() > 0.0) n.normalize();
      for (const Vec3* v : {static_cast<const Vec3*>(&n), &a, &b, &c}) {
        for (int k = 0; k < 3; ++k) put(out, static_cast<float>((*v)[k]));
      }
      put(out, std::uint16_t{0});
    }
  }
  return out;
}

std::string obj(const std::vector<Solid>& solids, const std::vector<std::string>& names, const std::string& comment) {
  std::string out = "# phedra thick plates: one object a plate, hinge part or body, each of closed shells\n";
  if (!comment.empty()) out += "# " + comment + "\n";
  std::size_t base = 1;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    out += "o " + names[k] + "\n";
    for (const Vec3& v : solids[k].vertices) out += "v " + number(v.x()) + " " + number(v.y()) + " " + number(v.z()) + "\n";
    for (const auto& t : solids[k].triangles) {
      out += "f " + std::to_string(base + t[0]) + " " + std::to_string(base + t[1]) + " " + std::to_string(base + t[2]) + "\n";
    }
    base += solids[k].vertices.size();
  }
  return out;
}

std::string model_xml(const std::vector<Solid>& solids, const std::vector<std::string>& names, const std::string& comment) {
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<model unit=\"millimeter\" xml:lang=\"en-US\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n"
      " <metadata name=\"Application\">phedra</metadata>\n";
  if (!comment.empty()) out += " <metadata name=\"Description\">" + xml_escape(comment) + "</metadata>\n";
  out += " <resources>\n";
  for (std::size_t k = 0; k < solids.size(); ++k) {
    out += "  <object id=\"" + std::to_string(k + 1) + "\" type=\"model\" name=\"" + xml_escape(names[k]) + "\">\n   <mesh>\n    <vertices>\n";
    for (const Vec3& v : solids[k].vertices) {
      out += "     <vertex x=\"" + number(v.x()) + "\" y=\"" + number(v.y()) + "\" z=\"" + number(v.z()) + "\"/>\n";
    }
    out += "    </vertices>\n    <triangles>\n";
    for (const auto& t : solids[k].triangles) {
      out += "     <triangle v1=\"" + std::to_string(t[0]) + "\" v2=\"" + std::to_string(t[1]) + "\" v3=\"" + std::to_string(t[2]) + "\"/>\n";
    }
    out += "    </triangles>\n   </mesh>\n  </object>\n";
  }
  out += " </resources>\n <build>\n";
  for (std::size_t k = 0; k < solids.size(); ++k) out += "  <item objectid=\"" + std::to_string(k + 1) + "\"/>\n";
  out += " </build>\n</model>\n";
  return out;
}

/// A zip archive of uncompressed ("stored") entries: the container of a 3MF file.
std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string out, directory;
  constexpr std::uint16_t version = 20, dos_time = 0, dos_date = (2026 - 1980) << 9 | 1 << 5 | 1;
  for (const auto& [name, data] : entries) {
    const auto offset = static_cast<std::uint32_t>(out.size());
    const auto crc = static_cast<std::uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
    const auto size = static_cast<std::uint32_t>(data.size());
    const auto name_length = static_cast<std::uint16_t>(name.size());
    put(out, std::uint32_t{0x04034b50});
    for (std::uint16_t v : {version, std::uint16_t{0}, std::uint16_t{0}, dos_time, dos_date}) put(out, v);
    for (std::uint32_t v : {crc, size, size}) put(out, v);
    put(out, name_length);
    put(out, std::uint16_t{0});
    out += name;
    out += data;
    put(directory, std::uint32_t{0x02014b50});
    for (std::uint16_t v : {version, version, std::uint16_t{0}, std::uint16_t{0}, dos_time, dos_date}) put(directory, v);
    for (std::uint32_t v : {crc, size, size}) put(directory, v);
    for (std::uint16_t v : {name_length, std::uint16_t{0}, std::uint16_t{0}, std::uint16_t{0}, std::uint16_t{0}}) {
      put(directory, v);
    }
    put(directory, std::uint32_t{0});
    put(directory, offset);
    directory += name;
  }
  const auto directory_offset = static_cast<std::uint32_t>(out.size());
  out += directory;
  put(out, std::uint32_t{0x06054b50});
  const auto count = static_cast<std::uint16_t>(entries.size());
  for (std::uint16_t v : {std::uint16_t{0}, std::uint16_t{0}, count, count}) put(out, v);
  put(out, static_cast<std::uint32_t>(directory.size()));
  put(out, directory_offset);
  put(out, std::uint16_t{0});
  return out;
}

std::string three_mf(const std::vector<Solid>& solids, const std::vector<std::string>& names, const std::string& comment,
                     const std::string& one_object) {
  if (!one_object.empty()) {  // one object, one mesh of every solid's shells: a slicer places it whole
    Solid all;
    for (const Solid& solid : solids) {
      const std::size_t base = all.vertices.size();
      all.vertices.insert(all.vertices.end(), solid.vertices.begin(), solid.vertices.end());
      for (const auto& t : solid.triangles) all.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
    return three_mf({all}, {one_object}, comment, "");
  }
  const std::string types =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">"
      "<Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>"
      "<Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>\n";
  const std::string rels =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
      "<Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
      "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>\n";
  return stored_zip({{"[Content_Types].xml", types}, {"_rels/.rels", rels}, {"3D/3dmodel.model", model_xml(solids, names, comment)}});
}

}  // namespace

bool is_solid_format(const std::string& extension) {
  return extension == ".stl" || extension == ".obj" || extension == ".3mf";
}

std::string solid_bytes(const std::vector<Solid>& solids, const std::vector<std::string>& names, const std::string& extension,
                        const std::string& comment, const std::string& one_object) {
  require_finite(solids);
  if (names.size() != solids.size()) throw Error(ExitCode::internal, "solid_bytes: one name a solid");
  if (extension == ".stl") return stl(solids, comment);
  if (extension == ".obj") return obj(solids, names, comment);
  if (extension == ".3mf") return three_mf(solids, names, comment, one_object);
  throw InvalidInputError("output", "thick plates are written as .stl, .obj or .3mf (not \"" + extension + "\")");
}

}  // namespace phedra
