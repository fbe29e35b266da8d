// The phedra core for the browser (issue 8): embind bindings over the same
// library the command uses. A Designer holds one design built from preset text;
// every call either answers or returns {ok: false, field, message} (the CLI's
// validation messages), never throws into JavaScript.

#include "phedra/assembly_check.h"
#include "phedra/assembly_mesh.h"
#include "phedra/buildability.h"
#include "phedra/panel_nets.h"
#include "phedra/design.h"
#include "phedra/energy_landscape.h"
#include "phedra/mechanics_figures.h"
#include "phedra/errors.h"
#include "phedra/fold_export.h"
#include "phedra/gltf_export.h"
#include "phedra/preset.h"
#include "phedra/keep_buildable.h"
#include "phedra/repair.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/optimize.h"
#include "phedra/self_intersection.h"
#include "phedra/design_preset.h"
#include "phedra/thick_plates.h"

#include <nlohmann/json.hpp>

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace {

using emscripten::val;
using namespace phedra;

/// The fields a repair or an optimization changed: [{field, before, after (JSON text), change, relative}].
val changes_val(const std::vector<FieldChange>& changes) {
  val out = val::array();
  for (const FieldChange& c : changes) {
    val change = val::object();
    change.set("field", c.field);
    change.set("before", c.before.dump());
    change.set("after", c.after.dump());
    change.set("change", c.change);
    change.set("relative", c.relative);
    out.call<void>("push", change);
  }
  return out;
}

val failure(const std::string& field, const std::string& message) {
  val v = val::object();
  v.set("ok", false);
  v.set("field", field);
  v.set("message", message);
  return v;
}

/// body()'s answer, or the failure its error says (options as JSON text: "options").
template <class Body>
val answer(Body&& body) {
  try {
    return body();
  } catch (const InvalidInputError& e) {
    return failure(e.field(), e.reason());
  } catch (const Error& e) {
    return failure("", e.what());
  } catch (const nlohmann::json::exception& e) {
    return failure("options", e.what());
  }
}

class Designer {
 public:
  /// Builds the design of a preset (JSON text). {ok: true} or {ok: false, field, message};
  /// a preset that fails leaves the previous design in place.
  val load(const std::string& text) {
    try {
      return build(parse_json_text(text));
    } catch (const InvalidInputError& e) {
      return failure(e.field(), e.reason());
    } catch (const Error& e) {
      return failure("", e.what());
    }
  }

  /// An edit while dragging, without the round trip through JSON text. `key` is a
  /// path of member names and array indices joined by dots ("trajectory",
  /// "tube.apex_heights", "grid.u_heights", "couplings.2.free_heights"): sets entry
  /// `index` of the list there to (x, y, z) (trajectory, directions) or to x (heights),
  /// or with index -1 the number there to x ("couplings.1.free_height"), and rebuilds.
  /// Refused: the previous design and preset stay.
  val set(const std::string& key, int index, double x, double y, double z) {
    if (!design_) return failure("", "no design loaded");
    nlohmann::json* entry = entry_at(key, index);
    if (!entry) return failure(key, "no such entry " + std::to_string(index));
    const nlohmann::json previous = *entry;
    *entry = entry->is_array() ? nlohmann::json::array({x, y, z}) : nlohmann::json(x);
    try {
      return build(document_);
    } catch (const InvalidInputError& e) {
      *entry = previous;
      return failure(e.field(), e.reason());
    } catch (const Error& e) {
      *entry = previous;
      return failure("", e.what());
    }
  }

  /// A keep-buildable drag step (issue 14): as set, then the rest of the design
  /// (its apex heights) projected onto the designs whose panels are all simple
  /// and whose t* is free of collisions, the held entry staying where the pointer
  /// put it, within `budget_ms` (cheap first: the drag's last projected step
  /// continued, the held height's neighbours following it; KeepBuildableDrag).
  /// When no such design is found in time, the held
  /// entry moves towards the pointer only as far as the design stays buildable
  /// at t* (bisection), like a handle against a wall. The motion over the whole
  /// interval is for the page to check when the hand stops. `also_fixed`: further
  /// fields that stay (a JSON array of JSON pointers, e.g. the field that defines
  /// t*; "" for none). {ok: true, projected, clamped, evaluations, how} or {ok:
  /// false, field, message} (a refused value: the previous design stays).
  val keep(const std::string& key, int index, double x, double y, double z, double budget_ms,
           const std::string& also_fixed) {
    if (!design_) return failure("", "no design loaded");
    nlohmann::json* entry = entry_at(key, index);
    if (!entry) return failure(key, "no such entry " + std::to_string(index));
    const nlohmann::json previous = *entry;
    const nlohmann::json wanted = entry->is_array() ? nlohmann::json::array({x, y, z}) : nlohmann::json(x);
    std::string pointer = "/" + key;
    for (char& c : pointer) c = c == '.' ? '/' : c;
    if (index >= 0) pointer += "/" + std::to_string(index);
    try {
      *entry = wanted;
      ProjectionOptions options;
      options.max_seconds = budget_ms / 1000.0;
      if (!also_fixed.empty()) {
        for (const nlohmann::json& f : nlohmann::json::parse(also_fixed)) {
          if (f.is_string() && f.get<std::string>() != pointer) options.fixed.push_back(f.get<std::string>());
        }
      }
      std::optional<Projection> p = drag_.step(document_, pointer, previous, options);
      bool clamped = false;
      std::size_t evaluations = p ? p->evaluations : 0;
      if (!p) {
        // Against the wall: the furthest buildable point towards the pointer.
        double good = 0.0, bad = 1.0;
        for (int step = 0; step < 5; ++step) {
          const double middle = 0.5 * (good + bad);
          *entry = between(previous, wanted, middle);
          bool ok = false;
          try {
            ok = drag_.buildable(design_from_json(document_));
          } catch (const InvalidInputError&) {
          }
          ++evaluations;
          (ok ? good : bad) = middle;
        }
        *entry = between(previous, wanted, good);
        clamped = true;
      }
      if (p && p->design) {
        document_ = std::move(p->preset);
        build(std::move(*p->design));
      } else {
        if (p) document_ = std::move(p->preset);
        build(document_);
      }
      val v = val::object();
      v.set("ok", true);
      v.set("projected", p ? p->moved : false);
      v.set("clamped", clamped);
      v.set("evaluations", static_cast<double>(evaluations));
      v.set("how", p ? p->how : std::string("clamped"));
      return v;
    } catch (const InvalidInputError& e) {
      *entry_at(key, index) = previous;
      return failure(e.field(), e.reason());
    } catch (const Error& e) {
      *entry_at(key, index) = previous;
      return failure("", e.what());
    }
  }

  /// The preset of the shown design (JSON text): what a keep-buildable drag made of it.
  std::string presetText() const { return document_.dump(); }

 private:
  /// Entry `index` of the list at `key` (see set), or with index -1 the number there; null if none.
  nlohmann::json* entry_at(const std::string& key, int index) {
    nlohmann::json* target = at_path(key);
    if (target && target->is_array() && index >= 0 && static_cast<std::size_t>(index) < target->size()) {
      return &(*target)[static_cast<std::size_t>(index)];
    }
    if (target && target->is_number() && index == -1) return target;
    return nullptr;
  }

  /// a + s (b - a) for numbers or equal-length arrays of numbers.
  static nlohmann::json between(const nlohmann::json& a, const nlohmann::json& b, double s) {
    if (a.is_number()) return a.get<double>() + s * (b.get<double>() - a.get<double>());
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t k = 0; k < a.size(); ++k) out.push_back(a[k].get<double>() + s * (b[k].get<double>() - a[k].get<double>()));
    return out;
  }

  /// The value at a dotted path of the preset (see set), or null.
  nlohmann::json* at_path(const std::string& key) {
    nlohmann::json* node = &document_;
    std::size_t start = 0;
    while (node && start <= key.size()) {
      const std::size_t end = std::min(key.find('.', start), key.size());
      const std::string part = key.substr(start, end - start);
      const bool numeric = !part.empty() && part.size() < 10 && part.find_first_not_of("0123456789") == std::string::npos;
      if (node->is_object() && node->contains(part)) {
        node = &(*node)[part];
      } else if (node->is_array() && numeric && std::stoul(part) < node->size()) {
        node = &(*node)[std::stoul(part)];
      } else {
        node = nullptr;
      }
      start = end + 1;
    }
    return node;
  }

  val build(const nlohmann::json& document) {
    Design design = design_from_json(document);
    if (&document != &document_) document_ = document;
    return build(std::move(design));
  }

  /// Shows `design` (that of document_); the panel mesh is kept when it is the
  /// same (a drag step).
  val build(Design&& design) {
    if (!design_ || !same_panel_mesh(*design_, design)) {
      mesh_ = panel_mesh(design);
      positions_.assign(3 * mesh_.vertices.size(), 0.0);
      faces_.clear();
      for (const Quad& q : mesh_.faces) {
        for (std::size_t c : q) faces_.push_back(static_cast<std::uint32_t>(c));
      }
    }
    plates_.reset();  // its plates refer to the design it replaces
    design_.emplace(std::move(design));
    val ok = val::object();
    ok.set("ok", true);
    return ok;
  }

 public:
  bool loaded() const { return design_.has_value(); }

  /// What `phedra info --json` says first: name, kind, t*, the interval and its limits, counts.
  val info() const {
    if (!design_) return failure("", "no design loaded");
    const Assembly& a = design_->assembly;
    val v = val::object();
    v.set("ok", true);
    v.set("name", a.name());
    v.set("kind", design_->kind);
    v.set("t_star", a.t_star());
    // t is the axis coordinate of this apex of the base (what an edit of it moves t* with).
    v.set("moving_apex", std::string(a.base().motion_case() == MotionCase::a ? "S_0" : "S_1"));
    v.set("t_lambda", a.flexion_interval().lower.t);
    v.set("t_mu", a.flexion_interval().upper.t);
    v.set("lambda_strip", static_cast<double>(a.flexion_interval().lower.strip));
    v.set("mu_strip", static_cast<double>(a.flexion_interval().upper.strip));
    v.set("members", static_cast<double>(a.member_count()));
    v.set("closed", a.closed(0));
    v.set("vertices", static_cast<double>(mesh_.vertices.size()));
    v.set("faces", static_cast<double>(mesh_.faces.size()));
    v.set("model_size", a.model_size());
    return v;
  }

  /// Quads as vertex indices (4 a face), a view into the module's memory: copy it.
  val faces() const { return val(emscripten::typed_memory_view(faces_.size(), faces_.data())); }

  /// Vertex positions at t (x, y, z a vertex, preset frame), a view into the
  /// module's memory valid until the next call: copy or use at once. Outside the
  /// flexion interval: {ok: false, ...}.
  val evaluate(double t) {
    if (!design_) return failure("", "no design loaded");
    try {
      design_->assembly.evaluate(t, configuration_);
    } catch (const Error& e) {
      return failure("t", e.what());
    }
    for (std::size_t k = 0; k < mesh_.vertices.size(); ++k) {
      const VertexRef& r = mesh_.vertices[k];
      const Vec3& p = configuration_.members[r.member][r.vertex];
      positions_[3 * k] = p.x();
      positions_[3 * k + 1] = p.y();
      positions_[3 * k + 2] = p.z();
    }
    return val(emscripten::typed_memory_view(positions_.size(), positions_.data()));
  }

  /// The apexes S_0..S_n of the base at t (x, y, z each, preset frame): on the axis, the line
  /// pi_0 and pi_1 share, which stays in place during the motion.
  val apexes(double t) {
    if (!design_) return failure("", "no design loaded");
    const PHedron& base = design_->assembly.base();
    try {
      const std::vector<double> heights = base.apex_heights(t);
      apexes_.clear();
      for (double h : heights) {
        const Vec3 p = base.frame().point_to_user(Vec3(0.0, 0.0, base.frame().height_to_canonical(h)));
        apexes_.insert(apexes_.end(), {p.x(), p.y(), p.z()});
      }
    } catch (const Error& e) {
      return failure("t", e.what());
    }
    return val(emscripten::typed_memory_view(apexes_.size(), apexes_.data()));
  }

  /// The check figures over `samples` configurations (relative to the model size).
  val check(int samples) const {
    if (!design_) return failure("", "no design loaded");
    CheckOptions options;
    options.samples = static_cast<std::size_t>(std::max(2, samples));
    const AssemblyCheckReport r = check_assembly(design_->assembly, options);
    const double size = design_->assembly.model_size();
    val v = val::object();
    v.set("ok", true);
    v.set("passed", r.passed());
    v.set("planarity", r.planarity.value / size);
    v.set("isometry", r.isometry.value / size);
    v.set("closure", r.closure.value / size);
    v.set("shared", r.shared.value / size);
    v.set("closed", r.closed);
    v.set("warning", r.warning);
    return v;
  }

  /// Whether the design can be built (docs/design.md): the panels' shapes with
  /// their causes, and with `sweep` the collision sweep of the motion
  /// (`samples` a side; 0: as the command, sweep_samples_for the panel count)
  /// and field hints for the first `hinted` invalid panels.
  /// {ok, buildable, summary, panels, bow_tie, degenerate, shape_margin,
  /// self_crossing, swept, interval: [a, b] or null, t_lambda, t_mu,
  /// invalid: [{panel, shape, cause, why, hints: [text]}],
  /// ends: [{side: "below" | "above", t, text, panels: [a, b]}],
  /// at_t_star: {text, panels: [a, b], hints: [text]} when t* itself collides, else null}.
  val buildability(bool sweep, int samples, int hinted) {
    if (!design_) return failure("", "no design loaded");
    try {
      BuildabilityOptions options;
      options.sweep_motion = sweep;
      options.sweep.samples_per_side = static_cast<std::size_t>(std::max(0, samples));  // 0: sweep_samples_for(panels)
      options.diagnosis.hints = hinted > 0;
      options.diagnosis.max_hinted_panels = static_cast<std::size_t>(std::max(0, hinted));
      const BuildabilityReport r = assess_buildability(*design_, &preset_object(document_), options);
      val v = val::object();
      v.set("ok", true);
      v.set("buildable", r.buildable());
      v.set("summary", r.summary());
      v.set("panels", static_cast<double>(r.panels));
      v.set("bow_tie", static_cast<double>(r.count(PanelShape::bow_tie)));
      v.set("degenerate", static_cast<double>(r.count(PanelShape::degenerate)));
      v.set("oversized", static_cast<double>(r.count(PanelShape::oversized)));
      v.set("sliver", static_cast<double>(r.count(PanelShape::sliver)));
      v.set("shape_margin", r.shape_margin);
      v.set("self_crossing", !r.self_crossing_members.empty());
      v.set("swept", r.swept);
      v.set("t_lambda", r.t_lambda);
      v.set("t_mu", r.t_mu);
      const auto range = r.interval();
      if (range) {
        val interval = val::array();
        interval.call<void>("push", range->first);
        interval.call<void>("push", range->second);
        v.set("interval", interval);
      } else {
        v.set("interval", val::null());
      }
      val invalid = val::array();
      for (const PanelDiagnosis& d : r.invalid) {
        val p = val::object();
        p.set("panel", static_cast<double>(d.panel));
        p.set("shape", to_string(d.shape));
        p.set("cause", to_string(d.rule.cause));
        p.set("why", d.why);
        val hints = val::array();
        for (const FieldHint& h : d.hints) hints.call<void>("push", describe(h));
        p.set("hints", hints);
        invalid.call<void>("push", p);
      }
      v.set("invalid", invalid);
      // What ends the buildable part on each side (a collision, a hinge folded
      // through, the growth bound): the command's words and the panels.
      val ends = val::array();
      if (r.swept && !r.motion.at_t_star) {
        for (const auto& [side, hit] : {std::pair{"below", r.motion.lower}, std::pair{"above", r.motion.upper}}) {
          if (!hit) continue;
          val e = val::object();
          e.set("side", std::string(side));
          e.set("t", hit->t);
          e.set("text", describe(*hit, r.members > 1));
          val panels = val::array();
          panels.call<void>("push", static_cast<double>(hit->a.face));
          panels.call<void>("push", static_cast<double>(hit->b.face));
          e.set("panels", panels);
          ends.call<void>("push", e);
        }
      }
      v.set("ends", ends);
      // The configuration at t* itself collides: the panels, the command's words
      // and the fields that free it (collision_hints; with hints asked for).
      if (r.motion.at_t_star) {
        const Collision& c = *r.motion.at_t_star;
        val at = val::object();
        at.set("text", describe(c, r.members > 1));
        val panels = val::array();
        panels.call<void>("push", static_cast<double>(c.a.face));
        panels.call<void>("push", static_cast<double>(c.b.face));
        at.set("panels", panels);
        val hints = val::array();
        for (const FieldHint& h : r.collision_hints) hints.call<void>("push", describe(h));
        at.set("hints", hints);
        v.set("at_t_star", at);
      } else {
        v.set("at_t_star", val::null());
      }
      return v;
    } catch (const Error& e) {
      return failure("", e.what());
    }
  }

  /// The panels that cannot be built (bow-ties, degenerate, oversized, slivers): cheap enough for
  /// every drag step (one evaluation at t*). A view into the module's memory.
  val invalidPanels() {
    if (!design_) return failure("", "no design loaded");
    const std::vector<PanelShape> shapes = bounded_panel_shapes(design_->assembly, mesh_);
    invalid_.clear();
    for (std::size_t f = 0; f < shapes.size(); ++f) {
      if (!is_valid_panel(shapes[f])) invalid_.push_back(static_cast<std::uint32_t>(f));
    }
    return val(emscripten::typed_memory_view(invalid_.size(), invalid_.data()));
  }

  /// The panels that penetrate another at t, or whose hinge has folded through
  /// on the way from t* (the designer colours them): a view into the module's
  /// memory valid until the next call.
  val collisions(double t) {
    if (!design_) return failure("", "no design loaded");
    try {
      const std::vector<std::size_t> panels = colliding_panels(*design_, t, 32);
      collisions_.assign(panels.begin(), panels.end());
    } catch (const Error& e) {
      return failure("t", e.what());
    }
    return val(emscripten::typed_memory_view(collisions_.size(), collisions_.data()));
  }

  /// The animated .glb of the design, as `phedra generate -o X.glb` writes it
  /// (`morph`: morph targets instead of a node per panel; `cycle`: the whole
  /// configuration curve). A view into the module's memory: copy it at once.
  val glb(bool morph, bool cycle) {
    if (!design_) return failure("", "no design loaded");
    try {
      GltfOptions options;
      options.morph = morph;
      options.cycle = cycle;
      options.buildability = file_buildability();
      options.preset_text = document_.dump();
      glb_ = gltf_bytes(*design_, options);
    } catch (const Error& e) {
      return failure("", e.what());
    }
    return val(emscripten::typed_memory_view(glb_.size(), reinterpret_cast<const std::uint8_t*>(glb_.data())));
  }

  /// The figures `phedra optimize` targets (phedra metrics --json's `figures`):
  /// {ok: true, names: [...], figures: {name: value or null}}, or {ok: false, ...}.
  val figures() const {
    if (!design_) return failure("", "no design loaded");
    try {
      const MetricsReport r = metamaterial_metrics(*design_);
      val v = val::object();
      v.set("ok", true);
      val names = val::array(), values = val::object();
      for (const std::string& name : figure_names()) {
        names.call<void>("push", name);
        const std::optional<double> f = r.figure(name);
        values.set(name, f ? val(*f) : val::null());
      }
      v.set("names", names);
      v.set("figures", values);
      return v;
    } catch (const Error& e) {
      return failure("", e.what());
    }
  }

  /// The exact energy landscape of the motion (phedra mechanics --energy): the
  /// fold springs at rest at `rest_t` (JSON {rest_t, samples}). Returns {ok:
  /// true, rest_t, t: [...], E: [...], dE_dt: [... null at the limits],
  /// equilibria: [{t, kind, E, rest}], bistable, barrier, reverse_barrier,
  /// largest_E, folds}, or {ok: false, field, message}.
  val energy(const std::string& options_text) const {
    if (!design_) return failure("", "no design loaded");
    return answer([&] {
      const nlohmann::json o = options_text.empty() ? nlohmann::json::object() : parse_json_text(options_text);
      EnergyOptions options;
      options.rest_t = o.value("rest_t", design_->assembly.t_star());
      options.samples = o.value("samples", std::size_t{201});
      options.stiffness = default_stiffness(*design_);
      const nlohmann::json j = energy_landscape(*design_, options).to_json();
      val v = val::object();
      v.set("ok", true);
      val t = val::array(), e = val::array(), rate = val::array();
      for (const nlohmann::json& s : j["energy"]) {
        t.call<void>("push", s["t"].get<double>());
        e.call<void>("push", s["E"].get<double>());
        rate.call<void>("push", s["dE_dt"].is_null() ? val::null() : val(s["dE_dt"].get<double>()));
      }
      v.set("t", t);
      v.set("E", e);
      v.set("dE_dt", rate);
      val equilibria = val::array();
      for (const nlohmann::json& q : j["equilibria"]) {
        val item = val::object();
        item.set("t", q["t"].get<double>());
        item.set("kind", q["kind"].get<std::string>());
        item.set("E", q["E"].get<double>());
        item.set("rest", q["rest"].get<bool>());
        equilibria.call<void>("push", item);
      }
      v.set("equilibria", equilibria);
      for (const char* key : {"rest_t", "largest_E", "barrier", "reverse_barrier"}) {
        v.set(key, j[key].is_null() ? val::null() : val(j[key].get<double>()));
      }
      v.set("bistable", j["bistable"].get<bool>());
      v.set("folds", j["folds"].get<double>());
      return v;
    });
  }

  /// The nearest design whose figures meet targets, as `phedra optimize` finds it.
  /// `options_text`: JSON {targets: ["poisson.nu_12=-0.8", ...], vary:
  /// "apex_heights,directions", max_seconds: 10, fixed: [JSON pointers]}. Returns
  /// {ok: true, reached, targets: [{target, before, after, met}], buildable,
  /// buildability, binding, changes: [{field, before, after, change, relative}], preset (its text,
  /// "NAME-optimized", when reached), evaluations, seconds}, or {ok: false, field,
  /// message}. The shown design does not change (the page loads the result).
  val optimize(const std::string& options_text) const {
    if (!design_) return failure("", "no design loaded");
    return answer([&] {
      const nlohmann::json o = options_text.empty() ? nlohmann::json::object() : parse_json_text(options_text);
      OptimizeOptions options;
      for (const std::string& t : o.value("targets", std::vector<std::string>{})) options.targets.push_back(FigureTarget::parse(t));
      const std::string vary = o.value("vary", std::string("apex_heights,directions"));
      options.vary = parse_variable_groups(vary);
      options.max_seconds = o.value("max_seconds", 10.0);
      options.fixed = o.value("fixed", std::vector<std::string>{});
      const OptimizeResult r = phedra::optimize(document_, options);
      val v = val::object();
      v.set("ok", true);
      v.set("reached", r.reached);
      val targets = val::array();
      for (const TargetOutcome& t : r.targets) {
        val x = val::object();
        x.set("target", t.target);
        x.set("before", t.before ? val(*t.before) : val::null());
        x.set("after", t.after ? val(*t.after) : val::null());
        x.set("met", t.met);
        targets.call<void>("push", x);
      }
      v.set("targets", targets);
      v.set("buildable", r.buildable);
      v.set("buildability", r.buildability);
      v.set("binding", r.binding);
      v.set("changes", changes_val(r.changes));
      if (r.reached) v.set("preset", named_optimized(r.preset, document_.value("name", std::string("unnamed")), vary, r).dump(2));
      v.set("evaluations", static_cast<double>(r.evaluations));
      v.set("seconds", r.seconds);
      return v;
    });
  }

  /// The nearest buildable design, as `phedra repair` finds it. `options_text`:
  /// JSON {vary: "apex_heights,directions", require: 1, max_seconds: 10, fixed:
  /// ["/trajectory/3"] (fields that stay)}, each optional. Returns {ok: true, found, already_buildable, fraction, distance,
  /// before, after (summaries), changes: [{field, before, after, change,
  /// relative}], preset (its text, named "NAME-repaired", when found: buildable
  /// over the required part), closest (how close it came, when not),
  /// closest_fraction and closest_preset (when not found but a narrower part
  /// was reached: that design, "NAME-closest"), evaluations, starts, seconds}, or {ok:
  /// false, field, message}. The shown design does not change (the page loads
  /// the result, keeping the previous one for its undo).
  val repair(const std::string& options_text) const {
    if (!design_) return failure("", "no design loaded");
    return answer([&] {
      const nlohmann::json o = options_text.empty() ? nlohmann::json::object() : parse_json_text(options_text);
      RepairOptions options;
      const std::string vary = o.value("vary", std::string("apex_heights,directions"));
      options.vary = parse_variable_groups(vary);
      options.required_fraction = o.value("require", 1.0);
      options.max_seconds = o.value("max_seconds", 10.0);
      options.fixed = o.value("fixed", std::vector<std::string>{});
      const RepairResult r = phedra::repair(document_, options);
      val v = val::object();
      v.set("ok", true);
      v.set("found", r.found);
      v.set("already_buildable", r.already_buildable);
      v.set("fraction", r.fraction);
      v.set("distance", r.distance);
      v.set("before", r.before.summary());
      v.set("after", r.after.summary());
      v.set("changes", changes_val(r.changes));
      if (r.found && !r.already_buildable) {
        v.set("preset", named_result(r.preset, document_.value("name", std::string("unnamed")), vary, r).dump(2));
      }
      v.set("closest", r.closest);
      if (!r.found && !r.already_buildable && r.closest_fraction > 0.0 && r.closest_preset.is_object()) {
        // The widest part reached: not a repair, offered to load (the page says so).
        v.set("closest_fraction", r.closest_fraction);
        v.set("closest_preset", named_result(r.closest_preset, document_.value("name", std::string("unnamed")), vary, r).dump(2));
      }
      v.set("evaluations", static_cast<double>(r.evaluations));
      v.set("starts", static_cast<double>(r.starts));
      v.set("seconds", r.seconds);
      return v;
    });
  }

  /// Thick plates (docs/design.md, "Thick panels"), as `phedra check --thickness`:
  /// `options_text` JSON {thickness (model units), side: "auto" | "front" | "back",
  /// samples (a side; 0: as the command)}. Keeps the plates for plateTriangles.
  /// {ok: true, thickness, side, plates, smallest_bevel_degrees, volume,
  /// panel_area, interval: [a, b] or null (they collide at t*), at_t_star: text or
  /// null, ends: [{side, t, kind, text, panels: [a, b]}]} or {ok: false, field,
  /// message} (plates too thick for a panel: field "thickness", and `thickest`,
  /// the thickest plates that fit at t* on that side).
  val thick(const std::string& options_text) {
    if (!design_) return failure("", "no design loaded");
    return answer([&] {
      const nlohmann::json o = options_text.empty() ? nlohmann::json::object() : parse_json_text(options_text);
      ThickOptions options;
      options.thickness = o.value("thickness", 0.0);
      options.side = plate_side_from_string(o.value("side", std::string("auto")));
      options.samples_per_side = o.value("samples", std::size_t{0});
      plates_.reset();
      BuildabilityOptions quick;
      quick.diagnosis.hints = false;
      const BuildabilityReport buildability = assess_buildability(*design_, nullptr, quick);
      ThickReport r;
      try {
        r = check_thickness(*design_, buildability, options);
      } catch (const InvalidInputError& e) {
        if (e.field() != "--thickness") throw;
        // Too thick for a panel: the refusal and the thickest plates that fit at
        // t* on that side (the page says both and highlights the panel).
        val v = failure("thickness", e.reason());
        ThickOptions probe = options;
        probe.thickness = 1e-6 * design_->assembly.model_size();
        probe.find_thickest = true;
        try {
          const ThickReport fits = check_thickness(*design_, buildability, probe);
          if (fits.thickest) {
            v.set("thickest", *fits.thickest);
            v.set("thickest_side", to_string(fits.thickest_side));
          }
        } catch (const Error&) {
        }
        return v;
      }
      plates_.emplace(thick_plates(*design_, r));
      val v = val::object();
      v.set("ok", true);
      const nlohmann::json j = r.to_json();
      v.set("thickness", r.thickness);
      v.set("side", to_string(r.side));
      v.set("plates", static_cast<double>(r.plates));
      v.set("smallest_bevel_degrees", j["smallest_bevel_degrees"].get<double>());
      v.set("volume", r.volume);
      v.set("panel_area", r.panel_area);
      if (r.at_t_star) {
        v.set("interval", val::null());
        v.set("at_t_star", j["at_t_star"]["text"].get<std::string>());
      } else {
        val interval = val::array();
        interval.call<void>("push", r.thick_lower);
        interval.call<void>("push", r.thick_upper);
        v.set("interval", interval);
        v.set("at_t_star", val::null());
      }
      val ends = val::array();
      for (const char* side : {"lower", "upper"}) {
        if (j[side].is_null()) continue;
        val e = val::object();
        e.set("side", std::string(side[0] == 'l' ? "below" : "above"));
        e.set("t", j[side]["t"].get<double>());
        e.set("kind", j[side]["kind"].get<std::string>());
        e.set("text", j[side]["text"].get<std::string>());
        val panels = val::array();
        for (const auto& p : j[side]["panels"]) panels.call<void>("push", p.get<double>());
        e.set("panels", panels);
        ends.call<void>("push", e);
      }
      v.set("ends", ends);
      return v;
    });
  }

  /// The plates of the last thick() at t as triangles (x, y, z of each corner,
  /// three corners a triangle, outward), a view into the module's memory valid
  /// until the next call; empty without plates. Outside the flexion interval: {ok: false, ...}.
  val plateTriangles(double t) {
    if (!design_) return failure("", "no design loaded");
    triangles_.clear();
    if (!plates_) return val(emscripten::typed_memory_view(triangles_.size(), triangles_.data()));
    try {
      for (const Solid& solid : plates_->solids(plates_->positions(t))) {
        for (const auto& tri : solid.triangles) {
          for (std::size_t c : tri) {
            const Vec3& p = solid.vertices[c];
            triangles_.insert(triangles_.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
          }
        }
      }
    } catch (const Error& e) {
      return failure("t", e.what());
    }
    return val(emscripten::typed_memory_view(triangles_.size(), triangles_.data()));
  }

  /// FOLD text with `count` frames over the flexion interval (as `phedra generate -o X.fold --count N`).
  std::string fold(int count) const {
    if (!design_) return "";
    std::vector<double> ts;
    const FlexionInterval& f = design_->assembly.flexion_interval();
    const int n = std::max(2, count);
    for (int k = 0; k < n; ++k) ts.push_back(k + 1 == n ? f.upper.t : f.lower.t + (f.upper.t - f.lower.t) * k / (n - 1));
    return fold_json(*design_, ts, file_buildability());
  }

 private:
  /// What the files store, as the command computes it (no field hints).
  nlohmann::json file_buildability() const {
    BuildabilityOptions options;
    options.diagnosis.hints = false;
    return assess_buildability(*design_, nullptr, options).file_json();
  }

  std::optional<Design> design_;
  nlohmann::json document_;  ///< the preset of design_
  KeepBuildableDrag drag_;  ///< keep(): continues the last step's projection
  AssemblyMesh mesh_;
  AssemblyConfiguration configuration_;
  std::vector<double> positions_;
  std::vector<std::uint32_t> faces_;
  std::vector<double> apexes_;
  std::vector<std::uint32_t> collisions_, invalid_;
  std::string glb_;
  std::optional<ThickPlates> plates_;  ///< of design_ (reset with it)
  std::vector<float> triangles_;
};

}  // namespace

EMSCRIPTEN_BINDINGS(phedra) {
  emscripten::class_<Designer>("Designer")
      .constructor<>()
      .function("load", &Designer::load)
      .function("set", &Designer::set)
      .function("keep", &Designer::keep)
      .function("presetText", &Designer::presetText)
      .function("loaded", &Designer::loaded)
      .function("info", &Designer::info)
      .function("faces", &Designer::faces)
      .function("evaluate", &Designer::evaluate)
      .function("apexes", &Designer::apexes)
      .function("check", &Designer::check)
      .function("buildability", &Designer::buildability)
      .function("collisions", &Designer::collisions)
      .function("invalidPanels", &Designer::invalidPanels)
      .function("glb", &Designer::glb)
      .function("fold", &Designer::fold)
      .function("repair", &Designer::repair)
      .function("figures", &Designer::figures)
      .function("optimize", &Designer::optimize)
      .function("thick", &Designer::thick)
      .function("energy", &Designer::energy)
      .function("plateTriangles", &Designer::plateTriangles);
}
