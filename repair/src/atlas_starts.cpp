// An optimization's starts from a design-space atlas (phedra optimize --start).
#include "phedra/atlas_table.h"
#include "phedra/errors.h"
#include "phedra/optimize.h"
#include "phedra/preset_fields.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace phedra {

std::vector<std::pair<std::string, nlohmann::json>> atlas_starts(const std::string& path, const OptimizeOptions& options,
                                                                 std::size_t count) {
  std::vector<std::string> names{"done", "valid", "buildable"};
  for (const FigureTarget& t : options.targets) names.push_back(t.name);
  // The parameters' columns: their paths from the atlas's space, read first.
  const AtlasTable head = read_atlas(path, {});
  std::vector<std::string> parameters;
  for (const nlohmann::json& p : head.space.value("parameters", nlohmann::json::array())) {
    parameters.push_back(p.value("path", ""));
  }
  names.insert(names.end(), parameters.begin(), parameters.end());
  const AtlasTable table = read_atlas(path, names);
  std::vector<const FigureTarget*> known;
  std::string missing;
  for (const FigureTarget& t : options.targets) {
    if (table.has(t.name)) {
      known.push_back(&t);
    } else {
      missing += (missing.empty() ? "" : ", ") + t.name;
    }
  }
  if (known.empty() && !options.targets.empty()) {
    std::string figures;
    for (const nlohmann::json& f : table.space.value("figures", nlohmann::json::array())) {
      figures += (figures.empty() ? "" : ", ") + f.get<std::string>();
    }
    throw InvalidInputError("--start", path + ": the atlas has none of the targets' figures (" + missing +
                                           "); its figures: " + figures);
  }
  for (const std::string& p : parameters) {
    if (!table.has(p)) throw InvalidInputError("--start", path + ": the parameter " + p + " has no array");
  }
  const bool buildable = options.keep_buildable && table.has("buildable");
  std::vector<std::size_t> rows;
  std::vector<double> score(table.designs, 0.0);
  for (std::size_t i = 0; i < table.designs; ++i) {
    if (!(table.columns.at("done")[i] == 1.0 && table.columns.at("valid")[i] == 1.0)) continue;
    if (buildable && table.columns.at("buildable")[i] != 1.0) continue;
    for (const FigureTarget* t : known) {
      const double v = table.columns.at(t->name)[i];
      const double tol = std::max(options.relative_tolerance * std::abs(t->value), options.absolute_tolerance);
      double e = 500.0;  // undefined there: far from any goal
      if (std::isfinite(v)) {
        e = (v - t->value) / tol;
        if (t->kind == FigureTarget::Kind::at_least) e = std::min(e, 0.0);
        if (t->kind == FigureTarget::Kind::at_most) e = std::max(e, 0.0);
        if (t->kind == FigureTarget::Kind::equal && std::abs(e) <= 1.0) e = 0.0;
      }
      score[i] += e * e;
    }
    rows.push_back(i);
  }
  if (rows.empty()) {
    throw InvalidInputError("--start", path + ": no row of the atlas is done and valid" +
                                           std::string(buildable ? " and buildable" : ""));
  }
  std::stable_sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
  rows.resize(std::min(rows.size(), count));
  std::vector<std::pair<std::string, nlohmann::json>> out;
  for (const std::size_t i : rows) {
    std::vector<std::pair<std::string, double>> values;
    for (const std::string& p : parameters) values.emplace_back(p, table.columns.at(p)[i]);
    out.emplace_back("atlas row " + std::to_string(i), preset_with_fields(table.space.at("base"), values));
  }
  return out;
}

}  // namespace phedra
