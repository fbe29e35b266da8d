// check_thickness: the collision-free interval of thick plates (thick_plates.h).

#include "phedra/thick_plates.h"

#include "phedra/bisection.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <numbers>
#include <ostream>

namespace phedra {
// Named, not anonymous: the unity builds (CMake's, the WebAssembly one) put this
// file in one translation unit with self_intersection.cpp.
namespace thick_detail {

ThickLimit limit_of(const ThickPlates& plates, const ThickPlates::Contact& c, double t) {
  return {c.hinge ? ThickLimit::Kind::hinge : ThickLimit::Kind::plates, plates.panel_id(c.a), plates.panel_id(c.b), t};
}

/// Walks from t* to `end` (the thin free end); the first contact, bisected.
std::optional<ThickLimit> sweep_plates(const ThickPlates& plates, double end, std::size_t samples,
                                const std::vector<double>& at_star, double& free_end) {
  const Assembly& assembly = plates.design().assembly;
  const double t_star = assembly.t_star();
  const double width = assembly.flexion_interval().width();
  free_end = t_star;
  if (end == t_star) return std::nullopt;
  std::vector<double> good_openings = at_star, next;
  double good = t_star;
  for (std::size_t k = 1; k <= samples; ++k) {
    const double s = 1.0 - static_cast<double>(k) / static_cast<double>(samples);
    const double t = k >= samples ? end : t_star + (end - t_star) * (1.0 - s * s);
    std::optional<ThickPlates::Contact> hit = plates.collision(plates.positions(t), good_openings, next);
    if (!hit) {
      good = t;
      good_openings = next;
      free_end = t;
      continue;
    }
    const ThickPlates::Contact first = bisect_first_hit(good, t, 1e-12 * width, *hit, [&](double mid) {
      std::optional<ThickPlates::Contact> h = plates.collision(plates.positions(mid), good_openings, next);
      if (!h) good_openings = next;
      return h;
    });
    free_end = good;
    return limit_of(plates, first, good);
  }
  return std::nullopt;
}

ThickReport check_side(const Design& design, const BuildabilityReport& thin, const ThickOptions& options, PlateSide side,
                       std::pair<double, double> free) {
  const Assembly& assembly = design.assembly;
  ThickReport r;
  r.thickness = options.thickness;
  r.side = side;
  r.t_star = assembly.t_star();
  r.t_lambda = assembly.flexion_interval().lower.t;
  r.t_mu = assembly.flexion_interval().upper.t;
  const std::pair<double, double> bevel = options.bevel_range.value_or(free);
  r.bevel_lower = bevel.first;
  r.bevel_upper = bevel.second;
  r.members = assembly.member_count();
  const ThickPlates plates(design, options.thickness, side, bevel, options.hinge_gap);
  r.hinge_gap = options.hinge_gap;
  r.plates = plates.plates();
  r.smallest_bevel = plates.smallest_bevel();
  r.panel_area = plates.panel_area();
  const Points x = plates.positions(r.t_star);
  for (const Solid& s : plates.solids(x)) r.volume += s.volume();
  const std::vector<double> at_star = plates.openings(x);
  std::vector<double> next;
  r.thick_lower = r.thick_upper = r.t_star;
  if (const auto hit = plates.collision(x, at_star, next)) {
    r.at_t_star = limit_of(plates, *hit, r.t_star);
    return r;
  }
  const std::size_t samples = options.samples_per_side ? options.samples_per_side : sweep_samples_for(plates.plates());
  r.samples = 2 * samples + 1;
  r.lower = sweep_plates(plates, free.first, samples, at_star, r.thick_lower);
  r.upper = sweep_plates(plates, free.second, samples, at_star, r.thick_upper);
  // Reaching the thin free end: what ends that (if it is not the flexion limit) ends this too.
  auto thin_limit = [&](const std::optional<Collision>& c, double end) -> std::optional<ThickLimit> {
    if (!c) return std::nullopt;
    return ThickLimit{ThickLimit::Kind::thin, c->a, c->b, end};
  };
  if (!r.lower) r.lower = thin_limit(thin.motion.lower, free.first);
  if (!r.upper) r.upper = thin_limit(thin.motion.upper, free.second);
  return r;
}

/// Plates `thickness` thick fit at t*: every plate has a top face and none collides there.
bool fits_at_t_star(const Design& design, double thickness, PlateSide side, std::pair<double, double> bevel, double gap) {
  try {
    const ThickPlates plates(design, thickness, side, bevel, gap);
    const Points x = plates.positions(design.assembly.t_star());
    const std::vector<double> openings = plates.openings(x);
    std::vector<double> next;
    return !plates.collision(x, openings, next);
  } catch (const InvalidInputError&) {
    return false;
  }
}

/// The thickest plates that fit at t* (to 1 %), by bisection of the thickness's
/// logarithm between 1e-4 and 0.5 of the model size, each with its own hinge gap
/// (options.hinge_gap_at: a pin hinge's grows with the plates); 0 when not even
/// the thinnest fit. Independent of the thickness the options were made for.
double thickest_at_t_star(const Design& design, PlateSide side, std::pair<double, double> bevel, const ThickOptions& options) {
  const double size = design.assembly.model_size();
  auto fits = [&](double t) { return fits_at_t_star(design, t, side, bevel, options.hinge_gap_at(t)); };
  double lo = 1e-4 * size, hi = 0.5 * size;
  if (!fits(lo)) return 0.0;
  if (fits(hi)) return hi;
  while (hi / lo > 1.01) {
    const double mid = std::sqrt(lo * hi);
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

double width_of(const ThickReport& r) { return r.at_t_star ? -1.0 : r.thick_upper - r.thick_lower; }

std::string describe_limit(const ThickLimit& l, bool several) {
  const std::string pair = describe(l.a, several) + " and " + describe(l.b, several);
  switch (l.kind) {
    case ThickLimit::Kind::hinge:
      return "the bevels of " + pair + " meet at their hinge (the hinge closes further on the plate side than "
             "the bevels allow)";
    case ThickLimit::Kind::plates: return "the plates of " + pair + " collide";
    case ThickLimit::Kind::thin: return "the zero-thickness panels already collide there (" + pair + ")";
  }
  return pair;
}

nlohmann::json limit_json(const std::optional<ThickLimit>& l, bool several) {
  if (!l) return nullptr;
  const char* kind = l->kind == ThickLimit::Kind::hinge ? "hinge" : l->kind == ThickLimit::Kind::plates ? "plates" : "thin";
  return {{"kind", kind}, {"t", l->t}, {"panels", {l->a.face, l->b.face}}, {"text", describe_limit(*l, several)}};
}

}  // namespace thick_detail
using namespace thick_detail;

namespace {
/// The side with the wider thick interval (`automatic`).
ThickReport better_side(const Design& design, const BuildabilityReport& thin, const ThickOptions& options,
                        std::pair<double, double> free);
}  // namespace

ThickReport check_thickness(const Design& design, const BuildabilityReport& thin, const ThickOptions& options) {
  const std::optional<std::pair<double, double>> free = thin.interval();
  if (!free) {
    throw InvalidInputError("--thickness", "the design is not buildable at t* without thickness (" + thin.summary() +
                                               "): there are no panels to thicken");
  }
  ThickReport r;
  try {
    r = options.side != PlateSide::automatic ? check_side(design, thin, options, options.side, *free)
                                             : better_side(design, thin, options, *free);
  } catch (const InvalidInputError& e) {
    // Given in millimetres: refused in millimetres (ThickPlates words it "a plate T thick ...").
    const std::string said = "a plate " + format_human(options.thickness) + " thick ";
    if (!options.millimetres_per_unit || e.field() != "--thickness" || e.reason().rfind(said + "does not ", 0) != 0) throw;
    throw InvalidInputError("--thickness-mm", "plates " + format_human(*options.millimetres_per_unit * options.thickness) +
                                                  " mm thick do not " + e.reason().substr(said.size() + std::string("does not ").size()));
  }
  if (options.find_thickest) {
    r.thickest = thickest_at_t_star(design, r.side, {r.bevel_lower, r.bevel_upper}, options);
    if (options.side == PlateSide::automatic && r.at_t_star) {
      // Both sides collide at t*: the side that carries the thicker plates.
      const PlateSide other = r.side == PlateSide::front ? PlateSide::back : PlateSide::front;
      try {
        ThickReport o = check_side(design, thin, options, other, *free);
        o.thickest = thickest_at_t_star(design, other, {o.bevel_lower, o.bevel_upper}, options);
        const bool tie = std::abs(*o.thickest - *r.thickest) <= 0.01 * std::max(*o.thickest, *r.thickest);
        if ((!tie && *o.thickest > *r.thickest) || (tie && o.volume > r.volume)) r = o;
      } catch (const InvalidInputError&) {
        // its plates do not fit: this side stays
      }
    }
    r.thickest_side = r.side;
    if (options.side == PlateSide::automatic) {
      // Either side may carry them: the thickest plates are the thicker side's,
      // whichever side plates of this thickness chose (the figure does not depend on it).
      const PlateSide other = r.side == PlateSide::front ? PlateSide::back : PlateSide::front;
      const double there = thickest_at_t_star(design, other, {r.bevel_lower, r.bevel_upper}, options);
      if (there > *r.thickest) r.thickest = there, r.thickest_side = other;
    }
  }
  return r;
}

double thick_fraction(const ThickReport& r) {
  return r.at_t_star || !(r.t_mu > r.t_lambda) ? 0.0 : (r.thick_upper - r.thick_lower) / (r.t_mu - r.t_lambda);
}

std::optional<ThickFolding> thickest_folding(const Design& design, const BuildabilityReport& thin, const ThickOptions& options,
                                             double fraction) {
  std::optional<ThickFolding> best;
  const std::vector<PlateSide> sides = options.side == PlateSide::automatic ? std::vector<PlateSide>{PlateSide::front, PlateSide::back}
                                                                             : std::vector<PlateSide>{options.side};
  for (const PlateSide side : sides) {
    ThickOptions o = options;
    o.side = side;
    o.find_thickest = false;
    // The part plates `t` thick move over on this side (0 when they do not fit).
    auto covers = [&](double t) {
      o.thickness = t;
      o.hinge_gap = o.hinge_gap_at(t);
      try {
        return thick_fraction(check_thickness(design, thin, o));
      } catch (const InvalidInputError&) {
        return 0.0;
      }
    };
    ThickOptions probe = o;
    probe.thickness = 1e-4 * design.assembly.model_size();
    probe.hinge_gap = probe.hinge_gap_at(probe.thickness);
    probe.find_thickest = true;
    double hi = 0.0;
    try {
      const ThickReport r = check_thickness(design, thin, probe);
      hi = r.thickest.value_or(0.0);
    } catch (const InvalidInputError&) {
    }
    double lo = 1e-4 * design.assembly.model_size();
    if (!(hi > lo)) continue;
    double at_lo = covers(lo);
    if (at_lo < fraction) continue;
    if (const double at_hi = covers(hi); at_hi >= fraction) {
      lo = hi, at_lo = at_hi;
    } else {
      while (hi / lo > 1.02) {
        const double mid = std::sqrt(lo * hi);
        if (const double f = covers(mid); f >= fraction) {
          lo = mid, at_lo = f;
        } else {
          hi = mid;
        }
      }
    }
    if (!best || lo > best->thickness) best = ThickFolding{lo, side, at_lo};
  }
  return best;
}

namespace {
ThickReport better_side(const Design& design, const BuildabilityReport& thin, const ThickOptions& options,
                        std::pair<double, double> free) {
  // A side whose plates do not fit (a top face vanishes) leaves the other one.
  std::optional<ThickReport> front, back;
  std::optional<InvalidInputError> misfit;
  for (const PlateSide side : {PlateSide::front, PlateSide::back}) {
    try {
      (side == PlateSide::front ? front : back) = check_side(design, thin, options, side, free);
    } catch (const InvalidInputError& e) {
      if (!misfit) misfit = e;
    }
  }
  if (!front && !back) throw *misfit;
  if (!front) return *back;
  if (!back) return *front;
  // The wider thick interval; on a tie (both collide at t*, or both reach as far) the more material.
  const double front_width = width_of(*front), back_width = width_of(*back);
  if (back_width != front_width) return back_width > front_width ? *back : *front;
  return back->volume > front->volume ? *back : *front;
}
}  // namespace

ThickPlates thick_plates(const Design& design, const ThickReport& report) {
  return ThickPlates(design, report.thickness, report.side, {report.bevel_lower, report.bevel_upper}, report.hinge_gap);
}

nlohmann::json ThickReport::to_json() const {
  nlohmann::json j = {{"thickness", thickness},
                      {"side", to_string(side)},
                      {"plates", plates},
                      {"bevel_range", {bevel_lower, bevel_upper}},
                      {"smallest_bevel_degrees", smallest_bevel * 180.0 / std::numbers::pi},
                      {"volume", volume},
                      {"panel_area", panel_area},
                      {"hinge_gap", hinge_gap},
                      {"thickest_at_t_star", thickest ? nlohmann::json(*thickest) : nlohmann::json(nullptr)},
                      {"thickest_side", thickest ? nlohmann::json(to_string(thickest_side)) : nlohmann::json(nullptr)},
                      {"samples", samples},
                      {"at_t_star", limit_json(at_t_star, members > 1)},
                      {"lower", limit_json(lower, members > 1)},
                      {"upper", limit_json(upper, members > 1)}};
  j["thick_interval"] = at_t_star ? nlohmann::json(nullptr) : nlohmann::json::array({thick_lower, thick_upper});
  return j;
}

std::ostream& operator<<(std::ostream& out, const ThickReport& r) {
  const bool several = r.members > 1;
  out << "thick plates: " << format_human(r.thickness) << " thick on the " << to_string(r.side) << " side, "
      << r.plates << " plates, bevels cut for [" << format_human(r.bevel_lower) << ", " << format_human(r.bevel_upper)
      << "] (smallest " << format_human(r.smallest_bevel * 180.0 / std::numbers::pi) << " degrees)\n";
  out << "  volume " << format_human(r.volume) << " (thickness x panel area " << format_human(r.thickness * r.panel_area)
      << ")\n";
  if (r.thickest) {
    out << "  the thickest plates that fit at t*" << (r.thickest_side == r.side ? " on this side" : " (on the " + to_string(r.thickest_side) + " side)")
        << ": " << format_human(*r.thickest) << (*r.thickest > 0.0 ? " (to 1 %)" : " (none: even 1e-4 of the model size collide)") << '\n';
  }
  if (r.at_t_star) {
    out << "  at t* = " << format_human(r.t_star) << ": " << describe_limit(*r.at_t_star, several) << '\n';
    return out;
  }
  const bool whole = !r.lower && !r.upper && r.thick_lower == r.t_lambda && r.thick_upper == r.t_mu;
  out << "  thick interval [" << format_human(r.thick_lower) << ", " << format_human(r.thick_upper) << "]"
      << (whole ? ": the whole flexion interval" : " of the flexion interval [" + format_human(r.t_lambda) + ", " +
                                                      format_human(r.t_mu) + "]")
      << '\n';
  if (r.lower) out << "  below t = " << format_human(r.lower->t) << ": " << describe_limit(*r.lower, several) << '\n';
  if (r.upper) out << "  above t = " << format_human(r.upper->t) << ": " << describe_limit(*r.upper, several) << '\n';
  return out;
}

}  // namespace phedra
