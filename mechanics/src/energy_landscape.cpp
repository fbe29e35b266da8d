#include "phedra/energy_landscape.h"

#include "fold_kernel.h"
#include "vertex_nodes.h"
#include "phedra/report_values.h"

#include "phedra/errors.h"
#include "phedra/interval_check.h"
#include "phedra/metamaterial_metrics.h"
#include "phedra/number_format.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>

namespace phedra {

FoldEnergy::FoldEnergy(const Design& design, double rest_t, const StiffnessOptions& options)
    : design_(design), model_(design, design.assembly.evaluate(rest_t), options),
      kernel_(std::make_unique<FoldKernel>(model_)),
      places_(design.assembly.net_places(model_.mesh().node_vertex)),
      places_by_row_(design.assembly.places_by_row(places_)) {
  rest_angles_.resize(model_.fold_count());
  weight_.resize(model_.fold_count());
  for (std::size_t h = 0; h < rest_angles_.size(); ++h) {
    rest_angles_[h] = model_.angle(h, model_.positions());
    weight_[h] = model_.hinges()[h].stiffness * model_.hinges()[h].length;
  }
}

FoldEnergy::~FoldEnergy() = default;

void FoldEnergy::nodes_at(double t, Scratch& s) const {
  // Only the corner nodes (the kernel needs no centre), straight from the nets: no member's vertices written out.
  // (No closed member's closure column: neither the nodes nor the strain read it.)
  s.finite = design_.assembly.evaluate_canonical_rate(t, s.states, s.rates, false);
  design_.assembly.write_vertices(s.states, places_, s.x);
  if (s.finite) design_.assembly.write_vertices(s.rates, places_, s.v, NetWriter::Kind::rates);
}

bool FoldEnergy::load_lanes(const double* ts, Scratch& s) const {
  static_assert(lanes == Assembly::lanes && lanes == HomogenizedStrain::lanes);
  const Assembly& a = design_.assembly;
  s.lane_x.resize(3 * lanes * places_.size());
  s.lane_v.resize(3 * lanes * places_.size());
  return a.vertices_lanes(ts, places_, places_by_row_, s.lane_x.data(), s.lane_v.data(), s.assembly_lanes);
}

std::array<FoldEnergy::Value, FoldEnergy::lanes> FoldEnergy::evaluate_lanes(
    const std::vector<double>& near, std::array<std::vector<double>, lanes>& angles, Scratch& s) const {
  static_assert(lanes == FoldKernel::lanes && lanes == std::tuple_size_v<decltype(Scratch::lane_turns)>);
  const std::size_t n = rest_angles_.size();
  if (near.size() != n) throw Error(ExitCode::internal, "energy: the samples evaluated together need the angles near them");
  std::array<double*, lanes> angle_out;
  std::array<std::int8_t*, lanes> turn_out;
  for (std::size_t l = 0; l < lanes; ++l) {
    angles[l].resize(n);
    s.lane_turns[l].resize(n);
    angle_out[l] = angles[l].data();
    turn_out[l] = s.lane_turns[l].data();
  }
  std::array<FoldKernel::Sums, lanes> sums;
  kernel_->energy_lanes(s.lane_x.data(), s.lane_v.data(), near.data(), rest_angles_.data(), weight_.data(),
                        angle_out.data(), turn_out.data(), sums.data(), s.lane_frames);
  std::array<Value, lanes> out;
  for (std::size_t l = 0; l < lanes; ++l) {
    out[l].energy = sums[l].energy;
    out[l].rate = sums[l].rate;
    out[l].largest_turn = sums[l].largest;
  }
  return out;
}

FoldEnergy::Value FoldEnergy::evaluate_from(double t, const double* near, std::vector<double>& angles,
                                            Scratch& s) const {
  nodes_at(t, s);
  const std::size_t n = rest_angles_.size();
  angles.resize(n);
  s.turns.resize(n);
  const FoldKernel::Sums sums = kernel_->energy(s.x, s.finite ? &s.v : nullptr, near, rest_angles_.data(),
                                                weight_.data(), angles.data(), s.turns.data(), s.frames);
  Value out;
  out.energy = sums.energy;
  if (s.finite) out.rate = sums.rate;
  out.largest_turn = sums.largest;
  return out;
}

FoldEnergy::Value FoldEnergy::evaluate(double t, const std::vector<double>& near, std::vector<double>& angles,
                                       Scratch& s) const {
  return evaluate_from(t, near.empty() ? rest_angles_.data() : near.data(), angles, s);
}

FoldEnergy::Value FoldEnergy::evaluate_turned(double t, const std::vector<std::int8_t>& turns, std::vector<double>& angles,
                                              Scratch& s) const {
  s.turns = turns;
  return evaluate_from(t, nullptr, angles, s);
}

double FoldEnergy::energy(double t, std::vector<double>& angles, const std::vector<double>& near) const {
  Scratch scratch;
  return evaluate(t, near, angles, scratch).energy;
}

std::pair<double, std::optional<double>> FoldEnergy::energy_and_rate(double t, std::vector<double>& angles,
                                                                    const std::vector<double>& near) const {
  Scratch scratch;
  const Value v = evaluate(t, near, angles, scratch);
  return {v.energy, v.rate};
}

bool EnergyLandscape::bistable() const {
  return std::count_if(equilibria.begin(), equilibria.end(), [](const Equilibrium& e) { return e.minimum; }) >= 2;
}

namespace {

struct Point {
  double t = 0.0;
  double energy = 0.0;
  std::optional<double> rate;
  std::vector<double> angles;
};

/// E and dE/dt at `t`, the angles carried from `from` continuously: steps of at
/// most half a radian for any fold, halving the step where one turns faster.
/// `scratch` holds the configuration at `t` after it.
Point carried(const FoldEnergy& f, const Point& from, double t, FoldEnergy::Scratch& scratch, int depth = 0) {
  Point p{t, 0.0, std::nullopt, {}};
  const FoldEnergy::Value v = f.evaluate(t, from.angles, p.angles, scratch);
  p.energy = v.energy;
  p.rate = v.rate;
  if (v.largest_turn <= 0.5 || depth >= 30) return p;
  const Point middle = carried(f, from, 0.5 * (from.t + t), scratch, depth + 1);
  return carried(f, middle, t, scratch, depth + 1);
}

/// The folds' turns (a byte a fold) of the samples the equilibria's search may
/// evaluate again: those beside a change of sign of dE/dt, without dE/dt (a
/// flexion limit) or at either end of a walk (beside the rest state or another
/// walk's samples). Every sample's turns, 1000 samples of 36,590 folds, were 37 MB
/// of fresh memory: 9,000 page faults, about a tenth of the landscape's time.
/// A walk's samples come in order, each beside the one before; a sample's turns
/// wait (in one reused buffer) until the next one's dE/dt is known.
class TurnsKept {
 public:
  using Turns = std::optional<std::vector<std::int8_t>>;
  explicit TurnsKept(std::vector<Turns>& kept) : kept_(kept) {}
  TurnsKept(const TurnsKept&) = delete;
  TurnsKept& operator=(const TurnsKept&) = delete;
  ~TurnsKept() {
    if (previous_ && !previous_kept_) kept_[*previous_] = std::move(waiting_);
  }

  void record(std::size_t i, std::optional<double> rate, const std::vector<std::int8_t>& turns) {
    bool keep = !previous_;  // a walk's first sample
    if (previous_) {
      const bool opposite = rate && previous_rate_ && ((*rate < 0.0 && *previous_rate_ > 0.0) ||
                                                       (*rate > 0.0 && *previous_rate_ < 0.0));
      keep = !rate || !previous_rate_ || opposite;
      if (keep && !previous_kept_) kept_[*previous_] = waiting_;
    }
    if (keep) {
      kept_[i] = turns;
    } else {
      waiting_.assign(turns.begin(), turns.end());
    }
    previous_ = i;
    previous_rate_ = rate;
    previous_kept_ = keep;
  }

 private:
  std::vector<Turns>& kept_;
  std::optional<std::size_t> previous_;
  std::optional<double> previous_rate_;
  bool previous_kept_ = false;
  std::vector<std::int8_t> waiting_;
};

/// Runs `left` and `right` (on two threads for large work, not in WebAssembly).
void both(bool large, const std::function<void()>& left, const std::function<void()>& right) {
#ifndef __EMSCRIPTEN__
  if (large) {
    std::exception_ptr failure;
    std::thread other([&] {
      try {
        right();
      } catch (...) {
        failure = std::current_exception();
      }
    });
    try {
      left();
    } catch (...) {
      other.join();
      throw;
    }
    other.join();
    if (failure) std::rethrow_exception(failure);
    return;
  }
#endif
  left();
  right();
}

}  // namespace

EnergyLandscape energy_landscape(const Design& design, const EnergyOptions& options) {
  const Assembly& a = design.assembly;
  const double lo = a.flexion_interval().lower.t, hi = a.flexion_interval().upper.t;
  if (!(options.rest_t >= lo && options.rest_t <= hi)) {
    throw InvalidInputError("--rest-t", "the rest state t = " + format_number(options.rest_t) +
                                            " is outside the flexion interval [" + format_number(lo) + ", " +
                                            format_number(hi) + "]");
  }
  if (options.samples < 2) throw InvalidInputError("--samples", "must be at least 2 (both limits)");
  const FoldEnergy fold(design, options.rest_t, options.stiffness);
  EnergyLandscape out;
  out.name = a.name();
  out.rest_t = options.rest_t;
  out.t_lambda = lo;
  out.t_mu = hi;
  out.folds = fold.model().fold_count();

  std::vector<double> ts = interval_samples(lo, hi, options.samples);
  ts.push_back(options.rest_t);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  const std::size_t rest = static_cast<std::size_t>(std::find(ts.begin(), ts.end(), options.rest_t) - ts.begin());

  // The lengths of `phedra metrics` and the forces that hold them, from the configuration each evaluation leaves.
  const HomogenizedStrain strain(a, options.axes);
  out.axes = strain.axes();
  const std::array<double, 3> at_star = axis_extents(a.evaluate(a.t_star()).members, out.axes);
  // Each sample keeps E and dE/dt; those the equilibria's search may need again keep their
  // folds' turns too (theta continuous = raw + 2 pi turns, TurnsKept): their angles by
  // evaluating them again (a byte a fold, not eight).
  struct Kept {
    double t = 0.0, energy = 0.0;
    std::optional<double> rate;
  };
  const std::optional<std::vector<std::uint32_t>> at_nodes = vertex_nodes(fold, options.rest_t);
  const Points strain_weights = at_nodes ? strain.weights(*at_nodes, fold.model().corner_node_count()) : Points{};
  std::vector<Kept> points(ts.size());
  std::vector<TurnsKept::Turns> turns_kept(ts.size());
  out.samples.resize(ts.size());
  // The strain of the configuration an evaluation (or load_lane) leaves in the scratch.
  auto strain_of = [&](const FoldEnergy::Scratch& scratch) {
    return at_nodes ? strain.state_of(scratch.x, scratch.finite ? &scratch.v : nullptr, strain_weights)
                    : strain.state_of(scratch.states, scratch.finite ? &scratch.rates : nullptr);
  };
  auto record_state = [&](std::size_t i, double t, double energy, std::optional<double> rate,
                          const std::vector<std::int8_t>& turns, const HomogenizedStrain::State& state,
                          TurnsKept& kept_turns) {
    Kept& kept = points[i];
    kept.t = t;
    kept.energy = energy;
    kept.rate = rate;
    kept_turns.record(i, rate, turns);  // the evaluation at t that gave its angles
    EnergySample& s = out.samples[i];
    s.t = t;
    s.energy = energy;
    s.rate = rate;
    for (int k = 0; k < 3; ++k) {
      if (!state.stretch[k]) continue;
      s.length[k] = at_star[k] * *state.stretch[k];
      if (!rate || !state.rate[k]) continue;
      const double d_length = *s.length[k] * *state.rate[k];
      if (std::abs(d_length) * (hi - lo) > 1e-9 * *s.length[k]) s.force[k] = *rate / d_length;
    }
  };
  auto record = [&](std::size_t i, const Point& p, const FoldEnergy::Scratch& scratch, TurnsKept& kept_turns) {
    record_state(i, p.t, p.energy, p.rate, scratch.turns, strain_of(scratch), kept_turns);
  };
  Point at_rest{options.rest_t, 0.0, std::nullopt, {}};
  {
    FoldEnergy::Scratch scratch;
    const FoldEnergy::Value v = fold.evaluate(options.rest_t, fold.rest_angles(), at_rest.angles, scratch);
    at_rest.energy = v.energy;
    at_rest.rate = v.rate;
    TurnsKept kept_turns(turns_kept);
    record(rest, at_rest, scratch, kept_turns);
  }
  // Outwards from the rest state, each side in segments of its samples, each
  // walked by one thread. For large models on two threads: one thread walks the
  // longer side from the rest state, the other the shorter side; a thread whose
  // segment is done takes the far half of the unwalked samples of the segment
  // with the most left (when 16 or more), starting there afresh (its angles
  // nearest the rest angles): neither waits for the other while work is left,
  // whatever else the processors run. Joined afterwards: when the walk through a
  // segment reaches the next one's first sample with the same angles (the same
  // turns of every fold), the next segment is what one walk gives, bit for bit;
  // else (a fold turned past a half turn on the way) the rest of the side is
  // walked again from there.
  const bool large = options.two_threads && static_cast<double>(out.folds) * static_cast<double>(ts.size()) > 2e5;
  constexpr std::size_t lanes = FoldEnergy::lanes, least_taken = 16;
  struct Part {
    int direction = 1;                 ///< samples rest + direction k
    std::size_t first = 1, next = 1;  ///< its first k, and the first not yet walked
    std::size_t last = 0;             ///< its last k (lowered when another thread takes the far part)
    std::optional<std::vector<double>> start;  ///< a fresh start's angles at `first` (none: from the rest state)
    Point end;                        ///< the last point walked
  };
  std::deque<Part> segments;  // the sides' parts (stable references while parts are added)
  std::mutex claims;
  // Up to `lanes` samples from k on that are the segment's to walk (0: it is done); none past its last.
  auto claim = [&](Part& segment, std::size_t k) {
    const std::lock_guard<std::mutex> lock(claims);
    const std::size_t n = k > segment.last ? 0 : std::min(lanes, segment.last + 1 - k);
    segment.next = k + n;
    return n;
  };
  // Walks samples k = first, first + 1, ... of `segment` (claimed up to `lanes`
  // at a time) from `from`; the last point. Four at a time
  // (FoldEnergy::evaluate_lanes, each lane carried from the one before: what one
  // at a time gives, bit for bit), one at a time where a sample of the four is a
  // flexion limit, for the last few, from a sample where a fold turned by more
  // than half a radian since the one before (carried: the step halved), and all
  // of them where the strain needs every member vertex (no vertex-to-node map:
  // the lanes give no member's nets).
  auto walk = [&](Point from, Part& segment, std::size_t first, FoldEnergy::Scratch& scratch,
                  TurnsKept& kept_turns) {
    const int direction = segment.direction;
    auto index = [&](std::size_t k) { return direction > 0 ? rest + k : rest - k; };
    std::array<std::vector<double>, lanes> lane_angles;
    std::array<HomogenizedStrain::State, lanes> states;
    for (std::size_t k = first;;) {
      const std::size_t n = claim(segment, k);
      if (n == 0) break;
      const std::size_t group_end = k + n;
      std::array<double, lanes> lane_ts;
      for (std::size_t l = 0; l < n; ++l) lane_ts[l] = ts[index(k + l)];
      if (at_nodes && n == lanes && !from.angles.empty() && fold.load_lanes(lane_ts.data(), scratch)) {
        strain.states_of_lanes(scratch.lane_x.data(), scratch.lane_v.data(), strain_weights, states.data());
        const std::array<FoldEnergy::Value, lanes> values = fold.evaluate_lanes(from.angles, lane_angles, scratch);
        std::size_t l = 0;
        for (; l < lanes && values[l].largest_turn <= 0.5; ++l) {
          record_state(index(k + l), lane_ts[l], values[l].energy, values[l].rate, scratch.lane_turns[l], states[l],
                       kept_turns);
        }
        if (l > 0) {
          from.t = lane_ts[l - 1];
          from.energy = values[l - 1].energy;
          from.rate = values[l - 1].rate;
          std::swap(from.angles, lane_angles[l - 1]);
          k += l;
        }
      }
      for (; k < group_end; ++k) {
        from = carried(fold, from, ts[index(k)], scratch);
        record(index(k), from, scratch, kept_turns);
      }
    }
    return from;
  };
  // Walks `segment` to its end: from the rest state, or from a fresh start at its first sample.
  auto walk_segment = [&](Part& segment, FoldEnergy::Scratch& scratch) {
    TurnsKept kept_turns(turns_kept);
    Point from = at_rest;
    if (segment.start) {
      const std::size_t i = segment.direction > 0 ? rest + segment.first : rest - segment.first;
      from = Point{ts[i], 0.0, std::nullopt, {}};
      const FoldEnergy::Value v = fold.evaluate(from.t, fold.rest_angles(), from.angles, scratch);
      from.energy = v.energy;
      from.rate = v.rate;
      record(i, from, scratch, kept_turns);
      *segment.start = from.angles;
    }
    segment.end = walk(std::move(from), segment, segment.start ? segment.first + 1 : segment.first, scratch, kept_turns);
  };
  // The far half of the unwalked samples of the segment with the most left, as a new segment (none: too few left).
  auto take = [&]() -> Part* {
    const std::lock_guard<std::mutex> lock(claims);
    Part* most = nullptr;
    for (Part& s : segments) {
      if (s.last + 1 >= s.next + least_taken && (!most || s.last - s.next > most->last - most->next)) most = &s;
    }
    if (!most) return nullptr;
    const std::size_t from = most->next + (most->last + 1 - most->next) / 2;
    Part& taken = segments.emplace_back();
    taken.direction = most->direction;
    taken.first = taken.next = from;
    taken.last = most->last;
    taken.start.emplace();
    most->last = from - 1;
    return &taken;
  };
  const std::size_t right = ts.size() - 1 - rest, left = rest;
  const int longer = right >= left ? 1 : -1;
  const std::size_t long_count = std::max(right, left), short_count = std::min(right, left);
  Part& long_side = segments.emplace_back();
  long_side.direction = longer;
  long_side.last = long_count;
  Part& short_side = segments.emplace_back();
  short_side.direction = -longer;
  short_side.last = short_count;
  auto worker = [&](Part& first) {
    FoldEnergy::Scratch scratch;
    walk_segment(first, scratch);
    while (large) {
      Part* taken = take();
      if (!taken) break;
      walk_segment(*taken, scratch);
    }
  };
  both(large, [&] { worker(long_side); }, [&] { worker(short_side); });
  for (const int direction : {longer, -longer}) {
    std::vector<Part*> side;
    for (Part& s : segments) {
      if (s.direction == direction && s.first <= s.last) side.push_back(&s);
    }
    std::sort(side.begin(), side.end(), [](const Part* x, const Part* y) { return x->first < y->first; });
    for (std::size_t k = 1; k < side.size(); ++k) {
      FoldEnergy::Scratch scratch;
      const std::size_t first = side[k]->first, count = direction == longer ? long_count : short_count;
      auto index = [&](std::size_t j) { return direction > 0 ? rest + j : rest - j; };
      const Point joined = carried(fold, side[k - 1]->end, ts[index(first)], scratch);
      if (joined.angles == *side[k]->start) continue;
      for (std::size_t j = first; j <= count; ++j) turns_kept[index(j)].reset();
      TurnsKept kept_turns(turns_kept);
      record(index(first), joined, scratch, kept_turns);
      Part rest_of_side;
      rest_of_side.direction = direction;
      rest_of_side.first = rest_of_side.next = first + 1;
      rest_of_side.last = count;
      walk(joined, rest_of_side, first + 1, scratch, kept_turns);
      break;
    }
  }
  for (const Kept& p : points) out.largest_energy = std::max(out.largest_energy, p.energy);
  FoldEnergy::Scratch scratch;  // the equilibria's
  // Sample i with its angles (evaluated again with its turns).
  auto restore = [&](std::size_t i) {
    Point p{points[i].t, 0.0, std::nullopt, {}};
    if (!turns_kept[i]) throw Error(ExitCode::internal, "energy: sample " + std::to_string(i) + "'s turns were not kept");
    const FoldEnergy::Value v = fold.evaluate_turned(p.t, *turns_kept[i], p.angles, scratch);
    p.energy = v.energy;
    p.rate = v.rate;
    return p;
  };

  // Equilibria: the rest state, and every change of sign of dE/dt between samples.
  const double resolution = 1e-12 * (hi - lo);
  // At a flexion limit dE/dt is infinite, at the rest state zero: their signs
  // are the ones beside them, towards the other end of the pair, 1e-6 of the
  // interval away (closer, rounding in the positions, about 1e-15 of the model
  // size and more where the motion is ill-conditioned, can outweigh the rate).
  const double step = 1e-6 * (hi - lo);
  // From t a step towards `towards`, never past half the way (a rest state a
  // hair inside a flexion limit has its neighbouring sample closer than a step).
  auto beside = [&](double t, double towards) {
    const double by = std::min(step, 0.5 * std::abs(towards - t));
    return towards > t ? t + by : t - by;
  };
  // The sign of dE/dt at sample i as seen from the pair's other end (beside it when needed).
  auto sign_beside = [&](std::size_t i, double towards) -> std::optional<double> {
    if (i != rest && points[i].rate) return points[i].rate;
    return carried(fold, i == rest ? at_rest : restore(i), beside(points[i].t, towards), scratch).rate;
  };
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (i == rest) out.equilibria.push_back({options.rest_t, true, points[i].energy, true});
    const std::optional<double> left_rate = sign_beside(i, points[i + 1].t);
    const std::optional<double> right_rate = sign_beside(i + 1, points[i].t);
    if (!left_rate || !right_rate) continue;
    const bool rises = *left_rate < 0.0 && *right_rate > 0.0, falls = *left_rate > 0.0 && *right_rate < 0.0;
    if (!rises && !falls) {
      if (*right_rate == 0.0 && i + 2 < points.size() && points[i + 2].rate) {
        const double after = *points[i + 2].rate;
        if ((*left_rate < 0.0 && after > 0.0) || (*left_rate > 0.0 && after < 0.0)) {
          out.equilibria.push_back({points[i + 1].t, *left_rate < 0.0, points[i + 1].energy, false});
        }
      }
      continue;
    }
    // A change of sign: bisect from the left end, its angles restored.
    Point a_side = i == rest ? at_rest : restore(i);
    if (i == rest || !points[i].rate) {
      a_side = carried(fold, a_side, beside(a_side.t, points[i + 1].t), scratch);
    }
    const bool falling_left = *left_rate < 0.0;
    double b = points[i + 1].t;
    while (b - a_side.t > resolution) {
      const Point m = carried(fold, a_side, 0.5 * (a_side.t + b), scratch);
      if (!m.rate || *m.rate == 0.0) {
        a_side = m;
        b = m.t;
        break;
      }
      if ((*m.rate < 0.0) == falling_left) {
        a_side = m;
      } else {
        b = m.t;
      }
    }
    const Point root = carried(fold, a_side, 0.5 * (a_side.t + b), scratch);
    out.equilibria.push_back({root.t, rises, root.energy, false});
  }
  if (rest + 1 == points.size()) out.equilibria.push_back({options.rest_t, true, points[rest].energy, true});

  // Bistable: the barrier to the nearest other minimum, both ways.
  if (out.bistable()) {
    const auto rest_state = std::find_if(out.equilibria.begin(), out.equilibria.end(), [](const Equilibrium& e) { return e.rest; });
    std::optional<std::pair<double, double>> best;  // (distance in t, barrier)
    for (auto it = out.equilibria.begin(); it != out.equilibria.end(); ++it) {
      if (!it->minimum || it->rest) continue;
      const auto from = std::min(it, rest_state), to = std::max(it, rest_state);
      double peak = -std::numeric_limits<double>::infinity();
      for (auto e = from; e != to; ++e) {
        if (!e->minimum) peak = std::max(peak, e->energy);
      }
      const double distance = std::abs(it->t - options.rest_t);
      if (std::isfinite(peak) && (!best || distance < best->first)) {
        best = {distance, peak};
        out.barrier = peak - rest_state->energy;
        out.reverse_barrier = peak - it->energy;
      }
    }
  }
  return out;
}

nlohmann::json EnergyLandscape::to_json() const {
  nlohmann::json samples_json = nlohmann::json::array();
  for (const EnergySample& s : samples) {
    samples_json.push_back({{"t", s.t},
                            {"E", s.energy},
                            {"dE_dt", optional_json(s.rate)},
                            {"length", {optional_json(s.length[0]), optional_json(s.length[1]), optional_json(s.length[2])}},
                            {"force", {optional_json(s.force[0]), optional_json(s.force[1]), optional_json(s.force[2])}}});
  }
  nlohmann::json eq = nlohmann::json::array();
  for (const Equilibrium& e : equilibria) {
    eq.push_back({{"t", e.t}, {"kind", e.minimum ? "minimum" : "maximum"}, {"E", e.energy}, {"rest", e.rest}});
  }
  nlohmann::json axes_json = nlohmann::json::array();
  for (const Vec3& d : axes) axes_json.push_back({d.x(), d.y(), d.z()});
  return {{"rest_t", rest_t},
          {"t_lambda", t_lambda},
          {"t_mu", t_mu},
          {"folds", folds},
          {"largest_E", largest_energy},
          {"bistable", bistable()},
          {"barrier", optional_json(barrier)},
          {"reverse_barrier", optional_json(reverse_barrier)},
          {"axes", axes_json},
          {"energy", samples_json},
          {"equilibria", eq}};
}

std::string EnergyLandscape::to_csv() const {
  // The samples and the equilibria (dE/dt = 0 there; no lengths computed), in increasing t.
  std::vector<std::pair<double, std::string>> rows;
  for (const EnergySample& s : samples) {
    const bool rest = s.t == rest_t;
    std::string row = format_number(s.t) + "," + format_number(s.energy) + "," + csv_number(s.rate);
    for (int k = 0; k < 3; ++k) row += "," + csv_number(s.length[k]);
    for (int k = 0; k < 3; ++k) row += "," + csv_number(s.force[k]);
    rows.push_back({s.t, row + (rest ? ",rest minimum" : ",") + "\n"});
  }
  for (const Equilibrium& e : equilibria) {
    if (e.rest) continue;
    rows.push_back({e.t, format_number(e.t) + "," + format_number(e.energy) + ",0,,,,,,," +
                             (e.minimum ? "minimum" : "maximum") + "\n"});
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::string out = "t,E,dE_dt,L1,L2,L3,force_1,force_2,force_3,equilibrium\n";
  for (const auto& row : rows) out += row.second;
  return out;
}

}  // namespace phedra
