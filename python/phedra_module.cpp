// The Python module `phedra` (issue 26, docs/python.md): a design from a preset
// (a file, a dict or JSON text), its exact motion as numpy arrays, and the
// reports the command prints (check, buildability, metrics, mechanics) as
// dicts, repair, and the exports. Errors raise phedra.Error subclasses with the command's
// messages: phedra.InputError (exit 2 there, with .field), phedra.FileError (3).

#include "phedra/assembly_check.h"
#include "phedra/buildability.h"
#include "phedra/check_report.h"
#include "phedra/design_preset.h"
#include "phedra/errors.h"
#include "phedra/files.h"
#include "phedra/fold_export.h"
#include "phedra/mechanics_figures.h"
#include "phedra/mechanics_report.h"
#include "phedra/gltf_export.h"
#include "phedra/mesh_export.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/motion_document.h"
#include "phedra/number_format.h"
#include "phedra/preset.h"
#include "phedra/preset_fields.h"
#include "phedra/repair.h"
#include "phedra/optimize.h"
#include "phedra/panel_size.h"
#include "phedra/solid_export.h"
#include "phedra/thick_plates.h"

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
using json = nlohmann::json;

namespace phedra::python {
namespace {

/// JSON to Python objects (through the json module: exact for every number).
py::object to_python(const json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

json from_python(const py::handle& object) {
  return json::parse(py::module_::import("json").attr("dumps")(object).cast<std::string>());
}

/// A design with its preset and its motion document (labels, faces, positions).
/// The fields a repair or an optimization changed, as dicts {field, before, after, change, relative}.
py::list changes_list(const std::vector<FieldChange>& changes) {
  py::list out;
  for (const FieldChange& c : changes) {
    py::dict change;
    change["field"] = c.field;
    change["before"] = to_python(c.before);
    change["after"] = to_python(c.after);
    change["change"] = c.change;
    change["relative"] = c.relative;
    out.append(change);
  }
  return out;
}

/// Numbers as float64, contiguous.
using Numbers = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// An array-like of numbers (or one number: 0 dimensions); InvalidInputError
/// naming the keyword for anything else.
Numbers numbers(const py::object& object, const char* keyword) {
  const bool text = py::isinstance<py::str>(object) || py::isinstance<py::bytes>(object);
  if (!text && !object.is_none()) {
    Numbers converted = Numbers::ensure(object);
    if (converted) return converted;
  }
  throw InvalidInputError(keyword, std::string(keyword) + " must be a number or an array-like of numbers, got " +
                                       py::str(py::type::of(object).attr("__name__")).cast<std::string>());
}

/// Every figure Design.figures gives, in its order.
std::vector<std::string> all_figure_names() {
  std::vector<std::string> names = figure_names();
  names.insert(names.end(), {"buildable", "buildable_fraction", "thickest_at_t_star"});
  names.insert(names.end(), mechanics_figure_names().begin(), mechanics_figure_names().end());
  return names;
}

void check_figure_names(const std::vector<std::string>& names) {
  const std::vector<std::string> known = all_figure_names();
  for (const std::string& n : names) {
    if (std::find(known.begin(), known.end(), n) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InvalidInputError("names", "unknown figure \"" + n + "\"; known: " + list);
    }
  }
}

/// The size bounds as the command takes them: 0 (no bound) or 1 or more.
void check_size_bounds(double max_growth, double max_panel_ratio) {
  for (const auto& [value, name] : {std::pair{max_growth, "max_growth"}, std::pair{max_panel_ratio, "max_panel_ratio"}}) {
    if (!(value == 0.0 || value >= 1.0) || !std::isfinite(value)) {
      throw InvalidInputError(name, "must be 0 (no bound) or a number, 1 or more (got " +
                                        format_number(value) + ")");
    }
  }
}

class PyDesign {
 public:
  PyDesign(json preset, std::string source) : preset_(std::move(preset)), source_(std::move(source)) {
    design_ = std::make_shared<Design>(design_from_json(preset_));
    document_ = motion_document(*design_);
  }

  const json& preset() const { return preset_; }
  const std::string& source() const { return source_; }
  const Design& design() const { return *design_; }
  std::string name() const { return design_->assembly.name(); }
  std::string kind() const { return design_->kind; }
  double t_star() const { return document_.t_star; }
  std::pair<double, double> flexion_interval() const { return {document_.t_lambda, document_.t_mu}; }
  std::size_t vertex_count() const { return document_.labels.size(); }

  py::dict info() const {
    const Assembly& a = design_->assembly;
    py::dict d;
    d["name"] = name();
    d["kind"] = kind();
    d["t_star"] = t_star();
    d["flexion_interval"] = py::make_tuple(document_.t_lambda, document_.t_mu);
    py::list limits;  // as phedra info --json has them
    for (const FlexionLimit& limit : {a.flexion_interval().lower, a.flexion_interval().upper}) {
      py::dict l;
      l["t"] = limit.t;
      l["strip"] = limit.strip;
      l["cause"] = limit.cause();
      limits.append(l);
    }
    d["limits"] = limits;
    d["motion_case"] = document_.motion_case;
    d["members"] = a.member_count();
    d["vertices"] = vertex_count();
    d["faces"] = document_.faces.size();
    d["model_size"] = a.model_size();
    d["source"] = source_;
    return d;
  }

  /// The vertices at t, (V, 3): the array owns the positions (moved, not copied).
  py::array_t<double> evaluate(double t) const {
    auto points = std::make_unique<Points>();
    document_.positions(t, *points);
    const py::ssize_t rows = static_cast<py::ssize_t>(points->size());
    double* data = points->empty() ? nullptr : points->front().data();
    py::capsule owner(points.release(), [](void* p) { delete static_cast<Points*>(p); });
    return py::array_t<double>({rows, py::ssize_t{3}}, {py::ssize_t{3 * sizeof(double)}, py::ssize_t{sizeof(double)}}, data,
                               owner);
  }

  /// t at a fraction of the flexion interval (0: t_lambda, 1: t_mu, both exact),
  /// of a number or elementwise of an array-like (an array of the same shape).
  py::object t_at_fraction(const py::object& fractions) const {
    auto one = [&](double f) { return fraction_to_t(f, "fraction"); };
    const Numbers values = numbers(fractions, "fraction");
    if (values.ndim() == 0) return py::float_(one(values.at()));
    py::array_t<double> out(values.request().shape);
    const double* in = values.data();
    double* to = out.mutable_data();
    for (py::ssize_t i = 0; i < values.size(); ++i) to[i] = one(in[i]);
    return out;
  }

  /// t at fraction f of the flexion interval; InvalidInputError naming `keyword` outside [0, 1].
  double fraction_to_t(double f, const char* keyword) const {
    if (!(f >= 0.0 && f <= 1.0)) {
      throw InvalidInputError(keyword, std::string(keyword) + " must be in [0, 1] (0: t_lambda, 1: t_mu), got " +
                                           format_number(f));
    }
    return design_->assembly.t_at_fraction(f);
  }

  /// The vertices at each t of `ts`, or at each fraction of the flexion interval, (k, V, 3).
  py::array_t<double> sample(const py::object& ts_object, const py::object& fractions) const {
    if (!ts_object.is_none() && !fractions.is_none()) throw InvalidInputError("fractions", "give ts or fractions, not both");
    if (ts_object.is_none() && fractions.is_none()) {
      throw InvalidInputError("ts", "give ts (motion parameters t) or fractions= (of the flexion interval)");
    }
    const char* name = fractions.is_none() ? "ts" : "fractions";
    const Numbers values = numbers(fractions.is_none() ? ts_object : fractions, name);
    if (values.ndim() != 1) {
      throw InvalidInputError(name, std::string(name) + " must be a sequence of numbers (a 1-dimensional array-like), got " +
                                        (values.ndim() == 0 ? std::string("one number (for one t: evaluate(t))")
                                                            : std::to_string(values.ndim()) + " dimensions"));
    }
    std::vector<double> ts(values.data(), values.data() + values.size());
    if (!fractions.is_none()) {
      for (double& t : ts) t = fraction_to_t(t, "fractions");
    }
    const std::size_t v = vertex_count();
    py::array_t<double> out({static_cast<py::ssize_t>(ts.size()), static_cast<py::ssize_t>(v), py::ssize_t{3}});
    auto view = out.mutable_unchecked<3>();
    Points points;
    for (std::size_t k = 0; k < ts.size(); ++k) {
      document_.positions(ts[k], points);
      for (std::size_t i = 0; i < v; ++i) {
        for (int c = 0; c < 3; ++c) view(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(i), c) = points[i][c];
      }
    }
    return out;
  }

  /// The quads, (F, 4) vertex indices, as every export numbers them.
  py::array_t<std::int64_t> faces() const {
    py::array_t<std::int64_t> out({static_cast<py::ssize_t>(document_.faces.size()), py::ssize_t{4}});
    auto view = out.mutable_unchecked<2>();
    for (std::size_t f = 0; f < document_.faces.size(); ++f) {
      for (int c = 0; c < 4; ++c) view(static_cast<py::ssize_t>(f), c) = static_cast<std::int64_t>(document_.faces[f][c]);
    }
    return out;
  }

  std::vector<std::vector<std::size_t>> labels() const { return document_.labels; }

  /// Each vertex's number in the FOLD file (vertices that coincide over the whole motion share one).
  py::array_t<std::int64_t> fold_vertex() const {
    const FoldNumbering& n = numbering();
    py::array_t<std::int64_t> out(static_cast<py::ssize_t>(n.vertex.size()));
    auto view = out.mutable_unchecked<1>();
    for (std::size_t v = 0; v < n.vertex.size(); ++v) {
      view(static_cast<py::ssize_t>(v)) = n.vertex[v] == SIZE_MAX ? -1 : static_cast<std::int64_t>(n.vertex[v]);
    }
    return out;
  }

  /// Whether each face is a triangle: two of its corners the same point over the whole motion.
  py::array_t<bool> triangles() const {
    const FoldNumbering& n = numbering();
    py::array_t<bool> out(static_cast<py::ssize_t>(n.faces.size()));
    auto view = out.mutable_unchecked<1>();
    for (std::size_t f = 0; f < n.faces.size(); ++f) view(static_cast<py::ssize_t>(f)) = n.faces[f].size() == 3;
    return out;
  }

  py::object check(std::size_t samples, double tolerance) const {
    CheckOptions options;
    options.samples = samples;
    options.relative_tolerance = tolerance;
    return to_python(report_json(check_assembly(design_->assembly, options)));
  }

  py::object buildability(double max_growth, double max_panel_ratio) const {
    check_size_bounds(max_growth, max_panel_ratio);
    BuildabilityOptions options;
    options.bounds.max_growth = max_growth;
    options.bounds.max_edge_ratio = max_panel_ratio;
    return to_python(assess_buildability(*design_, &preset_object(preset_), options).to_json());
  }

  /// Thick plates as `phedra check --thickness` has them (the report as a dict).
  py::object thick(double thickness, const std::string& side, double hinge_gap) const {
    return to_python(thick_report(thickness, side, hinge_gap, true).to_json());
  }

  py::object metrics(std::size_t samples, const std::string& axes) const {
    MetricsOptions options;
    options.samples = samples;
    options.axes = parse_metrics_axes(axes);
    return to_python(metamaterial_metrics(*design_, options).to_json());
  }

  /// The named figures of the design as made (the atlas's columns, docs/atlas.md):
  /// metrics' `figures` (with `samples` and `axes` as phedra metrics has them),
  /// buildable and buildable_fraction (phedra check's buildability), the
  /// thickest plates that fit at t* for plates of `thickness` (phedra check
  /// --thickness's thickest_at_t_star) and the mechanics figures; None where
  /// undefined.
  py::dict figures(const std::vector<std::string>& names, std::size_t samples, const std::string& axes,
                   const std::optional<double>& thickness, double max_growth, double max_panel_ratio) const {
    check_figure_names(names);
    std::vector<std::string> mechanics;
    bool metrics = false, build = false;
    for (const std::string& n : names) {
      if (is_mechanics_figure(n)) {
        mechanics.push_back(n);
      } else if (n == "buildable" || n == "buildable_fraction" || n == "thickest_at_t_star") {
        build = true;
      } else {
        metrics = true;
      }
    }
    std::optional<MetricsReport> report;
    if (metrics) {
      MetricsOptions options;
      options.samples = samples;
      options.axes = parse_metrics_axes(axes);
      report = metamaterial_metrics(*design_, options);
    }
    std::optional<BuildabilityReport> buildability;
    check_size_bounds(max_growth, max_panel_ratio);
    if (build) {
      BuildabilityOptions options;
      options.bounds.max_growth = max_growth;
      options.bounds.max_edge_ratio = max_panel_ratio;
      buildability = assess_buildability(*design_, &preset_object(preset_), options);
    }
    std::optional<MechanicsFigures> figures;
    if (!mechanics.empty()) figures = mechanics_figures(*design_, mechanics);
    py::dict out;
    auto number = [](std::optional<double> v) -> py::object {
      if (!v || !std::isfinite(*v)) return py::none();
      return py::float_(*v);
    };
    for (const std::string& n : names) {
      if (n == "buildable") {
        out[n.c_str()] = py::bool_(buildability->buildable());
      } else if (n == "buildable_fraction") {
        const auto interval = buildability->interval();
        out[n.c_str()] = interval ? (interval->second - interval->first) / (document_.t_mu - document_.t_lambda) : 0.0;
      } else if (n == "thickest_at_t_star") {
        if (!thickness || !(*thickness > 0.0) || !std::isfinite(*thickness)) {
          throw InvalidInputError("thickness", "thickest_at_t_star needs thickness= (the plates' thickness, model units, "
                                               "a positive number)");
        }
        if (!buildability->interval()) {
          out[n.c_str()] = py::none();  // not buildable at t*: no panels to thicken
          continue;
        }
        ThickOptions options;
        options.find_thickest = true;
        options.thickness = *thickness;
        try {
          out[n.c_str()] = number(check_thickness(*design_, *buildability, options).thickest);
        } catch (const InvalidInputError&) {
          out[n.c_str()] = py::none();
        }
      } else if (n == "mechanics.bistable") {
        out[n.c_str()] = py::bool_(figures->bistable);
      } else if (is_mechanics_figure(n)) {
        out[n.c_str()] = number(figures->figure(n));
      } else {
        out[n.c_str()] = number(report->figure(n));
      }
    }
    return out;
  }

  /// phedra mechanics as a dict (its --json), with numpy arrays: the nodes, the
  /// modes (k, N, 3), the exact velocity, K as COO triplets, the energy curve.
  py::dict mechanics(std::optional<double> t, std::optional<double> fraction, const std::string& panels, double bar,
                     std::optional<double> fold, double bend, std::optional<std::pair<double, double>> material,
                     std::optional<double> thickness, std::size_t modes, std::optional<double> rest_t,
                     std::optional<double> rest_fraction, std::size_t samples, std::optional<std::size_t> over_interval) const {
    const Assembly& a = design_->assembly;
    auto in_interval = [&](double value, const char* name) {
      if (!a.flexion_interval().contains(value)) {
        throw InvalidInputError(name, std::string(name) + " = " + format_number(value) + " is outside the flexion interval [" +
                                          format_number(document_.t_lambda) + ", " + format_number(document_.t_mu) + "]");
      }
      return value;
    };
    auto at_fraction = [&](double f, const char* name) {
      if (!(f >= 0.0 && f <= 1.0)) {
        throw InvalidInputError(name, std::string(name) + " must be in [0, 1] (0: t_lambda, 1: t_mu), got " + format_number(f));
      }
      return a.t_at_fraction(f);
    };
    if (t && fraction) throw InvalidInputError("fraction", "give t or fraction, not both");
    if (rest_t && rest_fraction) throw InvalidInputError("rest_fraction", "give rest_t or rest_fraction, not both");
    MechanicsRequest request;
    request.t = t ? in_interval(*t, "t") : fraction ? at_fraction(*fraction, "fraction") : a.t_star();
    request.stiffness.panels = panels == "n4b5" ? PanelModel::n4b5 : PanelModel::n5b8;
    if (panels != "n4b5" && panels != "n5b8") throw InvalidInputError("panels", "\"" + panels + "\": n4b5 or n5b8");
    request.stiffness.bar = bar;
    request.stiffness.bend = bend;
    request.stiffness.fold = fold;
    if (material) {
      if (!thickness) throw InvalidInputError("thickness", "material=(E, nu) needs the plate thickness: thickness=T");
      request.stiffness.material = Material{material->first, material->second, *thickness, std::nullopt};
    } else if (thickness) {
      throw InvalidInputError("thickness", "only with material=(E, nu)");
    }
    request.modes = modes;
    request.over_interval = over_interval;
    if (rest_t || rest_fraction) {
      EnergyOptions e;
      e.rest_t = rest_t ? in_interval(*rest_t, "rest_t") : at_fraction(*rest_fraction, "rest_fraction");
      e.samples = samples;
      request.energy = e;
    }
    const MechanicsReport r = [&] {
      try {
        return mechanics_report(*design_, request);
      } catch (const InvalidInputError& e) {  // the command's option names as this method's keywords
        if (e.field().rfind("--", 0) != 0) throw;
        std::string name = e.field().substr(2);
        std::replace(name.begin(), name.end(), '-', '_');
        throw InvalidInputError(name, e.reason());
      }
    }();
    py::dict out = to_python(r.to_json());
    const BarHingeModel& model = *r.model;
    const py::ssize_t n = static_cast<py::ssize_t>(model.node_count());
    auto points = [&](const Points& x) {
      py::array_t<double> arr({n, py::ssize_t{3}});
      auto v = arr.mutable_unchecked<2>();
      for (py::ssize_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) v(i, c) = x[static_cast<std::size_t>(i)][c];
      return arr;
    };
    out["node_positions"] = points(model.positions());
    // Each corner node: a row of evaluate(t) at the same point (-1 for the n5b8 centres).
    Points rows;
    document_.positions(r.t, rows);
    const std::vector<std::size_t> same = [&] {
      Points all = model.positions();
      all.resize(model.corner_node_count());
      all.insert(all.end(), rows.begin(), rows.end());
      return coincident_points({all}, 1e-9 * a.model_size());
    }();
    std::vector<std::int64_t> node_vertex(static_cast<std::size_t>(n), -1);
    const std::size_t corners = model.corner_node_count();
    for (std::size_t k = corners; k < same.size(); ++k) {
      if (same[k] < corners && node_vertex[same[k]] < 0) node_vertex[same[k]] = static_cast<std::int64_t>(k - corners);
    }
    out["node_vertex"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(node_vertex.size()), node_vertex.data());
    const Eigen::MatrixXd& m = r.modes.modes;
    py::array_t<double> vectors({static_cast<py::ssize_t>(m.cols()), n, py::ssize_t{3}});
    auto mv = vectors.mutable_unchecked<3>();
    for (Eigen::Index k = 0; k < m.cols(); ++k)
      for (py::ssize_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) mv(k, i, c) = m(3 * i + c, k);
    out["modes"] = vectors;
    if (r.modes.velocity.size() > 0) {
      py::array_t<double> v({n, py::ssize_t{3}});
      auto vv = v.mutable_unchecked<2>();
      for (py::ssize_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) vv(i, c) = r.modes.velocity(3 * i + c);
      out["velocity"] = v;
    } else {
      out["velocity"] = py::none();
    }
    const Eigen::SparseMatrix<double> k = model.stiffness();
    std::vector<std::int64_t> row, col;
    std::vector<double> value;
    for (int c = 0; c < k.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(k, c); it; ++it) {
        row.push_back(it.row()), col.push_back(it.col()), value.push_back(it.value());
      }
    }
    py::dict coo;
    coo["row"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(row.size()), row.data());
    coo["col"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(col.size()), col.data());
    coo["value"] = py::array_t<double>(static_cast<py::ssize_t>(value.size()), value.data());
    coo["shape"] = py::make_tuple(k.rows(), k.cols());
    out["K"] = coo;
    if (r.energy) {
      const std::size_t count = r.energy->samples.size();
      py::array_t<double> ts(static_cast<py::ssize_t>(count)), es(static_cast<py::ssize_t>(count)),
          rates(static_cast<py::ssize_t>(count));
      for (std::size_t i = 0; i < count; ++i) {
        const EnergySample& s = r.energy->samples[i];
        ts.mutable_at(static_cast<py::ssize_t>(i)) = s.t;
        es.mutable_at(static_cast<py::ssize_t>(i)) = s.energy;
        rates.mutable_at(static_cast<py::ssize_t>(i)) = s.rate ? *s.rate : std::numeric_limits<double>::quiet_NaN();
      }
      py::dict curve;
      curve["t"] = ts;
      curve["E"] = es;
      curve["dE_dt"] = rates;  // NaN at the flexion limits, where it is infinite
      out["energy"] = curve;
    }
    return out;
  }

  /// The nearest buildable design (None when none was found) and the result as a dict.
  py::tuple repair(const std::string& vary, double require, const std::string& objective, double max_seconds) const {
    RepairOptions options;
    options.vary = parse_variable_groups(vary);
    options.required_fraction = require;
    options.max_seconds = max_seconds;
    if (objective != "distance" && objective != "fields") {
      throw InvalidInputError("objective", "\"" + objective + "\" is neither \"distance\" nor \"fields\"");
    }
    options.objective = objective == "fields" ? RepairObjective::fields : RepairObjective::distance;
    options.escalate = vary == "apex_heights,directions";
    RepairResult r;
    {
      py::gil_scoped_release release;
      r = phedra::repair(preset_object(preset_), options);
    }
    py::dict result;
    result["found"] = r.found;
    result["already_buildable"] = r.already_buildable;
    result["fraction"] = r.fraction;
    result["distance"] = r.distance;
    result["changes"] = changes_list(r.changes);
    result["nearest_changes"] = r.nearest_changes;
    result["escalated"] = r.escalated;
    result["before"] = to_python(r.before.file_json());
    result["after"] = to_python(r.after.file_json());
    result["notes"] = r.notes;
    result["closest"] = r.closest;
    // Not found: the closest design (the widest part reached, or the fewest panels not simple) to inspect.
    result["closest_fraction"] = r.found || r.already_buildable ? py::object(py::none()) : py::object(py::float_(r.closest_fraction));
    result["closest_design"] = r.found || r.already_buildable || !r.closest_preset.is_object()
                                   ? py::object(py::none())
                                   : py::cast(PyDesign(named_result(r.closest_preset, name(), vary, r), source_ + " (closest)"));
    result["seconds"] = r.seconds;
    py::object repaired = py::none();
    if (r.found && !r.already_buildable) {
      repaired = py::cast(PyDesign(named_result(r.preset, name(), vary, r), source_ + " (repaired)"));
    }
    return py::make_tuple(repaired, result);
  }

  /// The design nearest this one whose figures meet `targets` (a str, a list of
  /// str as --target takes them, or a dict {name: value} of equalities), and/or
  /// whose panels at t* pass near `fit` (a (k, 3) array of points): (Design or
  /// None, result dict) as phedra optimize --json.
  py::tuple optimize(const py::object& targets, const py::object& fit, std::optional<double> fit_tol,
                     const std::string& vary, bool keep_buildable, double tol, const std::string& axes,
                     double max_seconds, unsigned seed, const py::object& start) const {
    OptimizeOptions options;
    if (py::isinstance<py::str>(targets)) {
      options.targets.push_back(FigureTarget::parse(targets.cast<std::string>()));
    } else if (py::isinstance<py::dict>(targets)) {
      for (const auto& [name, value] : targets.cast<py::dict>()) {
        options.targets.push_back(FigureTarget::parse(py::str(name).cast<std::string>() + "=" + py::str(value).cast<std::string>()));
      }
    } else if (!targets.is_none()) {
      for (const py::handle& t : targets) options.targets.push_back(FigureTarget::parse(py::str(t).cast<std::string>()));
    }
    if (!fit.is_none()) {
      const py::array_t<double, py::array::c_style | py::array::forcecast> points(fit);
      if (points.ndim() != 2 || points.shape(1) != 3 || points.shape(0) < 3) {
        throw InvalidInputError("fit", "points as a (k, 3) array with k >= 3");
      }
      FitTarget f;
      for (py::ssize_t k = 0; k < points.shape(0); ++k) f.points.emplace_back(points.at(k, 0), points.at(k, 1), points.at(k, 2));
      FitTarget::check_points(f.points, "fit", "fit: ");
      f.tolerance = fit_tol ? *fit_tol : 0.01 * bounded_model_size(*design_, options.bounds);
      if (!(f.tolerance > 0.0)) throw InvalidInputError("fit_tol", "must be positive");
      options.fit = f;
    }
    options.vary = parse_variable_groups(vary);
    options.keep_buildable = keep_buildable;
    options.relative_tolerance = tol;
    options.axes = parse_metrics_axes(axes);
    options.max_seconds = max_seconds;
    options.seed = seed;
    if (!start.is_none()) {
      const std::string atlas = py::str(py::module_::import("os").attr("fspath")(start)).cast<std::string>();
      try {
        options.starts = atlas_starts(atlas, options, 8);
      } catch (const InvalidInputError& e) {
        throw InvalidInputError("start", e.reason());
      }
    }
    OptimizeResult r;
    {
      py::gil_scoped_release release;
      r = phedra::optimize(preset_object(preset_), options);
    }
    py::dict result;
    result["reached"] = r.reached;
    py::list outcomes;
    for (const TargetOutcome& t : r.targets) {
      py::dict o;
      o["target"] = t.target;
      o["before"] = t.before ? py::cast(*t.before) : py::none();
      o["after"] = t.after ? py::cast(*t.after) : py::none();
      o["met"] = t.met;
      o["error"] = t.error;
      outcomes.append(o);
    }
    result["targets"] = outcomes;
    result["buildable"] = r.buildable;
    result["buildability"] = r.buildability;
    result["binding"] = r.binding.empty() ? py::none() : py::cast(r.binding);
    result["changes"] = changes_list(r.changes);
    result["distance"] = r.distance;
    result["evaluations"] = r.evaluations;
    result["seconds"] = r.seconds;
    result["notes"] = r.notes;
    result["started_from"] = r.started_from.empty() ? py::none() : py::cast(r.started_from);
    const nlohmann::json named = named_optimized(r.preset, name(), vary, r);
    result["closest"] = r.reached ? py::none() : to_python(named);
    py::object optimized = py::none();
    if (r.reached) optimized = py::cast(PyDesign(named, source_ + " (optimized)"));
    return py::make_tuple(optimized, result);
  }

  /// Writes the design: .glb / .gltf (animated), .fold (frames over the
  /// interval), .json (the motion document), .obj / .ply (at t, default t*).
  void export_to(const std::string& path, std::size_t count, std::optional<double> t, std::optional<double> thickness,
                 const std::string& side, double hinge_gap, bool nodes, bool cycle) const {
    const std::string extension = std::filesystem::path(path).extension().string();
    const bool gltf = extension == ".glb" || extension == ".gltf";
    if (nodes && !gltf) throw InvalidInputError("nodes", "a rigid node a panel is a glTF (.glb, .gltf) representation");
    if (cycle && !gltf) throw InvalidInputError("cycle", "the configuration curve is exported as glTF (.glb, .gltf) only");
    if (cycle && t) throw InvalidInputError("cycle", "the whole cycle is an animation: not with a static t");
    std::string bytes;
    if (thickness) {  // thick plates as solids, as `phedra generate --thickness`
      if (!is_solid_format(extension)) {
        throw InvalidInputError("thickness", "thick plates are written as solids: .stl, .3mf or .obj (not \"" + extension + "\")");
      }
      const ThickReport report = thick_report(*thickness, side, hinge_gap);
      const ThickPlates plates = thick_plates(*design_, report);
      std::vector<std::string> names;
      for (std::size_t k = 0; k < plates.plates(); ++k) names.push_back("plate_" + std::to_string(plates.panel(k)));
      bytes = solid_bytes(plates.solids(plates.positions(t.value_or(document_.t_star))), names, extension);
    } else if (extension == ".stl" || extension == ".3mf") {
      throw InvalidInputError("thickness", "an " + extension.substr(1) + " file holds solids: give the plate thickness");
    } else if (extension == ".glb" || extension == ".gltf") {
      GltfOptions options;
      options.binary = extension == ".glb";
      if (t) options.static_t = *t;
      options.morph = !nodes;  // as phedra generate --nodes
      options.cycle = cycle;   // as phedra generate --cycle: through the flexion limits
      bytes = gltf_bytes(*design_, options);
    } else if (extension == ".fold" || extension == ".json") {
      if (count < 2) throw InvalidInputError("count", "at least 2 configurations over the interval");
      std::vector<double> ts;
      if (t) {
        ts.push_back(*t);
      } else {
        for (std::size_t k = 0; k < count; ++k) {
          ts.push_back(fraction_to_t(static_cast<double>(k) / static_cast<double>(count - 1), "count"));  // ends exact
        }
      }
      bytes = extension == ".fold" ? fold_json(*design_, ts) : motion_json(document_, ts);
    } else if (extension == ".obj" || extension == ".ply") {
      bytes = mesh_text(*design_, t.value_or(document_.t_star), extension);
    } else {
      throw InvalidInputError("path", "\"" + path + "\": the formats are .glb, .gltf, .fold, .json, .obj and .ply (and "
                                      ".stl, .3mf, .obj with a thickness)");
    }
    write_file_atomically(path, bytes);
  }

 private:
  ThickReport thick_report(double thickness, const std::string& side, double hinge_gap, bool thickest = false) const {
    ThickOptions options;
    options.find_thickest = thickest;
    options.thickness = thickness;
    options.side = plate_side_from_string(side);
    options.hinge_gap = hinge_gap;
    return check_thickness(*design_, assess_buildability(*design_), options);
  }

  const FoldNumbering& numbering() const {
    if (!numbering_) numbering_ = std::make_shared<FoldNumbering>(fold_numbering(*design_));
    return *numbering_;
  }

  json preset_;
  std::string source_;
  std::shared_ptr<Design> design_;
  MotionDocument document_;
  mutable std::shared_ptr<FoldNumbering> numbering_;  ///< computed when first asked
};

/// A design from a path (str or os.PathLike), a dict, or JSON text.
PyDesign load(const py::object& what) {
  if (py::isinstance<py::dict>(what)) return PyDesign(from_python(what), "a dict");
  if (py::isinstance<py::array>(what)) {
    throw InvalidInputError("preset", "a numpy array is not a preset: give a path, a dict (a preset object) or JSON text");
  }
  const std::string text = py::str(what).cast<std::string>();
  if (py::isinstance<py::str>(what) && !text.empty() && text.find_first_not_of(" \t\r\n") != std::string::npos &&
      text[text.find_first_not_of(" \t\r\n")] == '{') {
    json j;
    try {
      j = json::parse(text);
    } catch (const json::parse_error& e) {
      throw InvalidInputError("", std::string("the JSON text does not parse: ") + e.what());
    }
    return PyDesign(std::move(j), "JSON text");
  }
  json j;
  const std::string content = read_text_file(text);
  try {
    j = json::parse(content);
  } catch (const json::parse_error& e) {
    throw InvalidInputError("", text + ": not JSON: " + e.what());
  }
  return PyDesign(std::move(j), text);
}

}  // namespace
}  // namespace phedra::python

PYBIND11_MODULE(_core, m) {
  using namespace phedra::python;
  using phedra::preset_field_value;
  using phedra::preset_with_fields;
  using phedra::InvalidInputError;
  using phedra::python::PyDesign;
  m.doc() = "phedra's compiled core (import phedra): rigid-foldable P-hedra, their exact motion, buildability, "
            "repair and exports (docs/python.md)";
  m.attr("__version__") = PHEDRA_VERSION;

  static py::exception<phedra::Error> error(m, "Error");
  static py::exception<phedra::InvalidInputError> input_error(m, "InputError", error.ptr());
  static py::exception<phedra::IOError> file_error(m, "FileError", error.ptr());
  error.attr("__doc__") = "Every error of phedra's core: the message is what the command prints";
  input_error.attr("__doc__") =
      "A bad input (the command's exit 2): .field names the preset field or keyword as the command does "
      "('' for the whole input, 't' for a t outside the flexion interval, 'path' for an unknown export format)";
  file_error.attr("__doc__") = "A file that cannot be read or written (the command's exit 3)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const phedra::InvalidInputError& e) {
      // The preset field as the command names it ("" for the whole input); a command-line
      // option (--max-growth) as the keyword that gives it here (max_growth).
      std::string field = e.field(), message = e.what();
      if (field.rfind("--", 0) == 0) {
        const std::string option = field;
        field = option == "--plate-side" ? "side" : field.substr(2);  // the keywords named otherwise here
        std::replace(field.begin(), field.end(), '-', '_');
        for (std::size_t at = message.find(option); at != std::string::npos; at = message.find(option, at + field.size())) {
          message.replace(at, option.size(), field);
        }
      }
      py::object instance = py::reinterpret_borrow<py::object>(input_error.ptr())(message);
      instance.attr("field") = field;
      PyErr_SetObject(input_error.ptr(), instance.ptr());
    } catch (const phedra::IOError& e) {
      file_error(e.what());
    } catch (const phedra::Error& e) {
      error(e.what());
    }
  });

  py::class_<PyDesign>(m, "Design", "A P-hedron, tube or tube array built from a preset (phedra.load)")
      .def_property_readonly("name", &PyDesign::name, "The design's name, as phedra info prints it")
      .def_property_readonly("kind", &PyDesign::kind, "What it is ('P-hedron', 'parallelogram tube', '3 x 3 grid of parallelogram cells', ...)")
      .def_property_readonly("t_star", &PyDesign::t_star, "The input configuration's motion parameter t*")
      .def_property_readonly("flexion_interval", &PyDesign::flexion_interval, "(t_lambda, t_mu)")
      .def_property_readonly("faces", &PyDesign::faces, "The quads, an (F, 4) array of vertex indices, as every export numbers them")
      .def_property_readonly("labels", &PyDesign::labels, "Each vertex's [i, c] (or [member, i, c] in an array)")
      .def_property_readonly("triangles", &PyDesign::triangles,
                             "An (F,) bool array: True where a face has two corners at one point over the whole "
                             "motion (a triangle: compute its normal from its distinct corners)")
      .def_property_readonly("fold_vertex", &PyDesign::fold_vertex,
                             "A (V,) int array: each vertex's number in the FOLD export (vertices that coincide over "
                             "the whole motion share one; the FOLD file numbers them in the order its faces first use "
                             "them): fold['vertices_coords'][fold_vertex[v]] is evaluate(t)[v]")
      .def_property_readonly("preset", [](const PyDesign& d) { return to_python(d.preset()); }, "The preset (a dict)")
      .def("info", &PyDesign::info, "Name, kind, t*, the flexion interval, counts and the model size (a dict)")
      .def("evaluate", &PyDesign::evaluate, py::arg("t"),
           "The vertices at t, a (V, 3) array (phedra sample --t); InputError outside the flexion interval")
      .def("sample", &PyDesign::sample, py::arg("ts") = py::none(), py::kw_only(), py::arg("fractions") = py::none(),
           "The vertices at each t of ts (an array-like), or at each of fractions= of the flexion interval: a "
           "(k, V, 3) array")
      .def("t_at_fraction", &PyDesign::t_at_fraction, py::arg("fraction"),
           "t at a fraction of the flexion interval (0: t_lambda, 1: t_mu, both exact): of a number, or elementwise "
           "of an array-like")
      .def("check", &PyDesign::check, py::arg("samples") = 200, py::arg("tolerance") = 1e-9,
           "Planarity, isometry and closure over the flexion interval (phedra check's geometry, a dict)")
      .def("buildability", &PyDesign::buildability, py::arg("max_growth") = 10.0, py::arg("max_panel_ratio") = 100.0,
           "Whether it can be built and over which part of the motion (phedra check --json's buildability)")
      .def("metrics", &PyDesign::metrics, py::arg("samples") = 101, py::arg("axes") = "structural",
           "Metamaterial figures against t (phedra metrics --json)")
      .def("figures", &PyDesign::figures, py::arg("names"), py::kw_only(), py::arg("samples") = 101,
           py::arg("axes") = "structural", py::arg("thickness") = py::none(), py::arg("max_growth") = 10.0,
           py::arg("max_panel_ratio") = 100.0,
           "The named figures of the design as made, a dict name -> value (None where undefined): metrics' "
           "figures (as phedra metrics --json's 'figures', with samples and axes), buildable and "
           "buildable_fraction (the buildable part of the flexion interval, phedra check), thickest_at_t_star (the "
           "thickest plates that fit at t*, needs thickness=), the mechanics figures (mechanics.gap, ...); "
           "phedra.figure_names() lists them")
      .def("mechanics", &PyDesign::mechanics, py::kw_only(), py::arg("t") = py::none(), py::arg("fraction") = py::none(),
           py::arg("panels") = "n5b8", py::arg("bar") = 1e3, py::arg("fold") = py::none(), py::arg("bend") = 0.1,
           py::arg("material") = py::none(), py::arg("thickness") = py::none(), py::arg("modes") = 6,
           py::arg("rest_t") = py::none(), py::arg("rest_fraction") = py::none(), py::arg("samples") = 201,
           py::arg("over_interval") = py::none(),
           "phedra mechanics as a dict (the keys of --json) with numpy arrays: node_positions (N, 3), node_vertex "
           "(N,: the row of evaluate(t) at each corner node, -1 for n5b8 centres), modes (k, N, 3), velocity (N, 3, "
           "the exact dX/dt, rigid motions out; None at a flexion limit), K (COO: row, col, value, shape); with "
           "rest_t or rest_fraction the energy landscape: energy {t, E, dE_dt (NaN at the limits)}, equilibria, "
           "bistable, barrier")
      .def("repair", &PyDesign::repair, py::arg("vary") = "apex_heights,directions", py::arg("require") = 1.0,
           py::arg("objective") = "distance", py::arg("max_seconds") = 60.0,
           "The nearest design buildable over the required part (`require`, as --require): (Design or None, result dict) "
           "as phedra repair --json; when none is found, None and the result's closest_design (the widest part reached, or "
           "the fewest panels not simple) and closest_fraction")
      .def("optimize", &PyDesign::optimize, py::arg("targets") = py::none(), py::arg("fit") = py::none(),
           py::arg("fit_tol") = py::none(), py::arg("vary") = "apex_heights,directions", py::arg("keep_buildable") = true,
           py::arg("tol") = 0.02, py::arg("axes") = "structural", py::arg("max_seconds") = 60.0, py::arg("seed") = 1u,
           py::arg("start") = py::none(),
           "The nearest design whose figures meet the targets ('poisson.nu_12=-0.8', a list of them, or a dict of "
           "equalities) and/or that passes near fit points: (Design or None, result dict) as phedra optimize; "
           "start=ATLAS.zarr (a path): from the best of the atlas's rows, as --start")
      .def("thick", &PyDesign::thick, py::arg("thickness"), py::arg("side") = "auto", py::arg("hinge_gap") = 0.0,
           "Thick plates as `phedra check --thickness` has them: side, bevels, volume, the thick interval and what "
           "ends it (a dict)")
      .def("export", &PyDesign::export_to, py::arg("path"), py::arg("count") = 41, py::arg("t") = py::none(),
           py::arg("thickness") = py::none(), py::arg("side") = "auto", py::arg("hinge_gap") = 0.0,
           py::arg("nodes") = false, py::arg("cycle") = false,
           "Write .glb/.gltf (animated, or static at t; nodes=True: a rigid node a panel, as phedra generate --nodes; "
           "cycle=True: the whole configuration curve through the flexion limits, as --cycle), .fold/.json (count "
           "configurations, or t), .obj/.ply (at t, default t*); with a thickness, the plates as solids at t: .stl, "
           ".3mf or .obj")
      .def(py::pickle(
          // By its preset (a repaired or optimized design's is its own), so that it travels to other processes.
          [](const PyDesign& d) { return py::make_tuple(d.preset().dump(), d.source()); },
          [](const py::tuple& state) {
            if (state.size() != 2) throw std::runtime_error("phedra.Design: not a pickled design");
            return PyDesign(json::parse(state[0].cast<std::string>()), state[1].cast<std::string>());
          }))
      .def("__repr__", [](const PyDesign& d) {
        return "<phedra.Design '" + d.name() + "': " + d.kind() + ", " + std::to_string(d.vertex_count()) + " vertices>";
      });
  m.def("figure_names", &all_figure_names, "The names Design.figures (and an atlas's figures) take, in order");
  m.def(
      "preset_field",
      [](const py::object& preset, const std::string& path, const std::string& field) {
        return preset_field_value(from_python(preset), path, field.empty() ? path : field);
      },
      py::arg("preset"), py::arg("path"), py::arg("field") = "",
      "The number at a field path of a preset dict ('grid.u_heights[1]', 'trajectory[4][0]'; "
      "'directions[2].turn' is 0, a turn from the preset's direction, in degrees); InputError (its field "
      "`field`, default the path) when the preset has no such number or it follows others (a closed tube's "
      "repeated heights)");
  m.def(
      "with_fields",
      [](const py::object& preset, const py::dict& values) {
        std::vector<std::pair<std::string, double>> list;
        for (const auto& [key, value] : values) list.emplace_back(key.cast<std::string>(), value.cast<double>());
        return to_python(preset_with_fields(from_python(preset), list));
      },
      py::arg("preset"), py::arg("values"),
      "The preset dict with fields set by path ({'grid.u_heights[1]': 0.4, 'directions[2].turn': 10.0}: a "
      "direction turned about the axis by degrees); a closed tube's tied heights follow");
  m.def("load", &load, py::arg("preset"), "A design from a preset: a path, a dict, or JSON text");
}
