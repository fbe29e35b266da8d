#include "phedra/atlas_table.h"

#include "phedra/errors.h"
#include "phedra/files.h"

#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace phedra {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

json read_json(const fs::path& file, const std::string& field, const std::string& what) {
  try {
    return json::parse(read_text_file(file));
  } catch (const json::exception&) {
    throw InvalidInputError(field, file.string() + ": " + what + " is not JSON");
  }
}

struct ArrayLayout {
  std::size_t length = 0, chunk = 0, item = 0;
  bool boolean = false, zlib = false;
  double fill = std::numeric_limits<double>::quiet_NaN();
};

ArrayLayout layout_of(const fs::path& folder, const std::string& name, const std::string& field) {
  const json meta = read_json(folder / ".zarray", field, "the array " + name + "'s .zarray");
  auto refuse = [&](const std::string& why) {
    return InvalidInputError(field, folder.string() + ": the array " + name + " " + why +
                                        " (not as python3 -m phedra.atlas writes it)");
  };
  if (!meta.contains("shape") || meta["shape"].size() != 1 || !meta.contains("chunks") || meta["chunks"].size() != 1) {
    throw refuse("is not one-dimensional");
  }
  ArrayLayout a;
  a.length = meta["shape"][0].get<std::size_t>();
  a.chunk = meta["chunks"][0].get<std::size_t>();
  if (a.chunk == 0) throw refuse("has chunks of 0 rows");
  const std::string dtype = meta.value("dtype", "");
  if (dtype == "<f8") {
    a.item = 8;
  } else if (dtype == "|b1") {
    a.item = 1;
    a.boolean = true;
  } else {
    throw refuse("has the type " + dtype);
  }
  if (!meta.value("filters", json()).is_null()) throw refuse("has filters");
  const json& compressor = meta.value("compressor", json());
  if (!compressor.is_null()) {
    if (compressor.value("id", "") != "zlib") throw refuse("is compressed with " + compressor.value("id", "?"));
    a.zlib = true;
  }
  const json& fill = meta.value("fill_value", json());
  if (fill.is_number()) a.fill = fill.get<double>();
  if (fill.is_boolean()) a.fill = fill.get<bool>() ? 1.0 : 0.0;
  return a;
}

std::vector<double> read_column(const fs::path& atlas, const std::string& name, const std::string& field) {
  const fs::path folder = atlas / name;
  const ArrayLayout a = layout_of(folder, name, field);
  std::vector<double> out(a.length, a.fill);
  std::vector<unsigned char> raw(a.chunk * a.item);
  for (std::size_t first = 0, k = 0; first < a.length; first += a.chunk, ++k) {
    const fs::path file = folder / std::to_string(k);
    if (!fs::exists(file)) continue;  // never written: the fill value
    const std::string bytes = read_text_file(file);
    if (a.zlib) {
      uLongf size = static_cast<uLongf>(raw.size());
      if (uncompress(raw.data(), &size, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uLong>(bytes.size())) != Z_OK ||
          size != raw.size()) {
        throw InvalidInputError(field, file.string() + ": a damaged chunk of " + name + " (zlib)");
      }
    } else {
      if (bytes.size() != raw.size()) throw InvalidInputError(field, file.string() + ": a chunk of the wrong size");
      std::memcpy(raw.data(), bytes.data(), raw.size());
    }
    for (std::size_t i = 0; i < a.chunk && first + i < a.length; ++i) {
      if (a.boolean) {
        out[first + i] = raw[i] != 0 ? 1.0 : 0.0;
      } else {
        std::uint64_t bits = 0;
        for (int b = 7; b >= 0; --b) bits = (bits << 8) | raw[i * 8 + static_cast<std::size_t>(b)];  // little-endian
        out[first + i] = std::bit_cast<double>(bits);
      }
    }
  }
  return out;
}

}  // namespace

AtlasTable read_atlas(const fs::path& path, const std::vector<std::string>& names, const std::string& field) {
  if (!fs::is_directory(path) || !fs::exists(path / ".zattrs")) {
    throw InvalidInputError(field, path.string() + ": not an atlas (a Zarr store made by python3 -m phedra.atlas)");
  }
  const json attrs = read_json(path / ".zattrs", field, "the atlas's attributes (.zattrs)");
  if (attrs.value("format", "") != "phedra-atlas/1" || !attrs.contains("space")) {
    throw InvalidInputError(field, path.string() + ": a Zarr store, but not a phedra atlas");
  }
  AtlasTable t;
  t.space = attrs["space"];
  t.designs = t.space.value("designs", std::size_t{0});
  for (const std::string& name : names) {
    if (!fs::exists(path / name / ".zarray")) continue;
    std::vector<double> column = read_column(path, name, field);
    if (column.size() != t.designs) {
      throw InvalidInputError(field, path.string() + ": the array " + name + " has " + std::to_string(column.size()) +
                                         " rows, the atlas " + std::to_string(t.designs));
    }
    t.columns.emplace(name, std::move(column));
  }
  return t;
}

}  // namespace phedra
