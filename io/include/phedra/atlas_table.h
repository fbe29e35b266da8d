#pragma once
// Reading a design-space atlas (docs/atlas.md: a Zarr v2 store that
// python3 -m phedra.atlas writes): its attributes and the columns asked for,
// so that `phedra optimize --start ATLAS.zarr` starts from its best rows.
// Only what the atlas writer makes is read: one-dimensional arrays of
// little-endian float64 ("<f8") or bool ("|b1"), compressed with zlib or not.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace phedra {

struct AtlasTable {
  nlohmann::json space;  ///< the atlas's "space" attribute: base, parameters, figures, ...
  std::size_t designs = 0;
  /// The columns read, by name: bools as 0 and 1, NaN where missing.
  std::map<std::string, std::vector<double>> columns;
  /// Whether the atlas has an array of this name.
  bool has(const std::string& name) const { return columns.count(name) != 0; }
};

/// The atlas at `path` with the columns `names` it has (the others left out).
/// InvalidInputError(field) when it is not a phedra atlas or an array is not
/// one the writer makes; IOError when a file cannot be read.
AtlasTable read_atlas(const std::filesystem::path& path, const std::vector<std::string>& names,
                      const std::string& field = "--start");

}  // namespace phedra
