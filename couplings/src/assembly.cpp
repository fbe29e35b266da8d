#include "phedra/assembly.h"

#include "phedra/errors.h"
#include "phedra/geometry_checks.h"
#include "phedra/net_writer.h"
#include "phedra/tolerances.h"

#include <algorithm>
#include <numeric>

namespace phedra {

Assembly::Assembly(PHedron base, std::string base_name) : base_(std::move(base)) {
  const AxialNet axial = base_.axial_net();
  base_reference_ = {axial.vertices, build_parallel_net(axial, base_.canonical_input().trajectory).vertices,
                     base_.canonical_input().heights};
  Member m;
  m.name = std::move(base_name);
  m.closed = base_.closed();
  m.topology = base_.topology();
  m.reference = base_.reference();
  members_.push_back(std::move(m));
  model_size_ = base_.model_size();
}

std::size_t Assembly::add_member(const MemberSpec& spec) {
  if (spec.seed.parent >= members_.size()) {
    throw InvalidInputError(spec.field, "parent " + std::to_string(spec.seed.parent) + " does not exist (there are " +
                                            std::to_string(members_.size()) + " members so far)");
  }
  const std::size_t parent = spec.seed.parent;
  const NetState& parent_state =
      parent == 0 ? base_reference_ : members_[parent].seeded->reference_state();
  const std::size_t parent_columns = parent == 0 ? base_.motion().columns() : members_[parent].seeded->columns();
  if (members_[parent].closed && spec.seed.vertex_line >= parent_columns - 1) {
    throw InvalidInputError(spec.field, "vertex line " + std::to_string(spec.seed.vertex_line) + " does not exist: " +
                                            "the parent tube has " + std::to_string(parent_columns - 1) +
                                            " vertex lines (0.." + std::to_string(parent_columns - 2) + ")");
  }
  Member m;
  m.name = spec.name.empty() ? "member " + std::to_string(members_.size()) : spec.name;
  m.seeded.emplace(spec, parent_state, parent_columns, base_.canonical_input().directions, base_.frame(),
                   base_.canonical_input().scale);
  m.closed = m.seeded->closed();
  const std::size_t n = m.seeded->columns();
  m.topology = GridTopology(base_.topology().rows(), NetWriter::columns(m.closed, n), m.closed);
  m.reference.assign(m.topology.vertex_count(), Vec3::Zero());
  members_.push_back(std::move(m));
  write_user(members_.size() - 1, members_.back().seeded->reference_state(), members_.back().reference);
  for (const Vec3& p : members_.back().reference) {
    if (!p.allFinite()) throw InvalidInputError(spec.field, "the member's construction overflows (not finite)");
  }
  Points all;
  for (const Member& member : members_) all.insert(all.end(), member.reference.begin(), member.reference.end());
  model_size_ = bounding_box_diagonal(all);
  shared_.reset();
  return members_.size() - 1;
}

std::vector<double> Assembly::apex_heights(std::size_t m) const {
  std::vector<double> heights = m == 0 ? base_.canonical_input().heights : members_[m].seeded->heights();
  for (double& h : heights) h = base_.frame().height_to_user(h);
  return heights;
}

Sign Assembly::sign(std::size_t m) const {
  return m == 0 ? base_.input().signs.front() : members_[m].seeded->signs().front();
}

const std::vector<Sign>& Assembly::signs(std::size_t m) const {
  return m == 0 ? base_.input().signs : members_[m].seeded->signs();
}

std::size_t Assembly::total_vertex_count() const {
  std::size_t count = 0;
  for (const Member& m : members_) count += m.topology.vertex_count();
  return count;
}

void Assembly::write_user(std::size_t m, const NetState& state, Points& out, NetWriter::Kind kind) const {
  const std::size_t n = state.apexes.size() - 1;
  const NetWriter writer(base_.frame(), members_[m].closed, n, out, kind);
  const std::size_t rows = members_[m].topology.rows();
  for (std::size_t i = 0; i < rows; ++i) {
    writer.write(i, state.apexes.data(), &state.axial[i * n], &state.general[i * n]);
  }
}

void Assembly::evaluate_states(double t, std::vector<NetState>& states, const std::vector<bool>* flipped) const {
  states.resize(members_.size());
  base_.evaluate_canonical(t, states[0].axial, states[0].general, states[0].apexes, flipped);
  for (std::size_t m = 1; m < members_.size(); ++m) {
    const Seed& seed = members_[m].seeded->seed();
    const NetState& parent = states[seed.parent];
    members_[m].seeded->evaluate(parent, parent.apexes.size() - 1, states[m]);
  }
}

void Assembly::evaluate(double t, AssemblyConfiguration& out) const { evaluate_on(t, nullptr, out); }

void Assembly::evaluate(double t, const std::vector<bool>& flipped, AssemblyConfiguration& out) const {
  if (flipped.size() != base_.topology().rows()) {
    throw Error(ExitCode::internal, "evaluate: branch of " + std::to_string(flipped.size()) + " strips, expected " +
                                        std::to_string(base_.topology().rows()));
  }
  evaluate_on(t, &flipped, out);
}

void Assembly::evaluate_on(double t, const std::vector<bool>* flipped, AssemblyConfiguration& out) const {
  evaluate_states(t, out.states, flipped);
  out.t = t;
  write_configuration(out);
}

bool Assembly::evaluate_canonical_rate(double t, std::vector<NetState>& states, std::vector<NetState>& rates,
                                       bool closure) const {
  states.resize(members_.size());
  rates.resize(members_.size());
  const bool finite = base_.evaluate_canonical_rate(t, states[0], rates[0]);
  for (std::size_t m = 1; m < members_.size(); ++m) {
    const std::size_t parent = members_[m].seeded->seed().parent;
    const std::size_t columns = states[parent].apexes.size() - 1;
    members_[m].seeded->evaluate(states[parent], columns, states[m], closure);
    if (finite) members_[m].seeded->evaluate(rates[parent], columns, rates[m], closure);
  }
  return finite;
}

bool Assembly::evaluate_rate(double t, AssemblyConfiguration& out, std::vector<Points>& rates) const {
  const bool finite = evaluate_canonical_rate(t, out.states, out.rate_states);
  out.t = t;
  write_configuration(out);
  if (!finite) return false;
  rates.resize(members_.size());
  for (std::size_t m = 0; m < members_.size(); ++m) {
    rates[m].resize(members_[m].topology.vertex_count());
    write_user(m, out.rate_states[m], rates[m], NetWriter::Kind::rates);
  }
  return true;
}

std::vector<Assembly::NetPlace> Assembly::net_places(std::span<const VertexRef> vertices) const {
  std::vector<NetPlace> out;
  out.reserve(vertices.size());
  for (const VertexRef& v : vertices) {
    const bool closed = members_[v.member].closed;
    const std::size_t columns = members_[v.member].topology.columns();
    const std::size_t n = closed ? columns + 1 : columns - 2;  // NetWriter::columns inverted
    const std::size_t i = v.vertex / columns, c = v.vertex % columns;
    // NetWriter::canonical's choice of entry.
    const std::size_t j = closed ? c : c == 0 ? 0 : c == n + 1 ? n - 1 : c - 1;
    const std::uint32_t boundary = closed ? 0 : c == 0 ? 1 : c == n + 1 ? 2 : 0;
    out.push_back({static_cast<std::uint32_t>(v.member), static_cast<std::uint32_t>(i * n + j), boundary});
  }
  return out;
}

void Assembly::write_vertices(const std::vector<NetState>& states, std::span<const NetPlace> places, Points& out,
                              NetWriter::Kind kind) const {
  // What NetWriter::write computes for the entry, in the same order (the same bits).
  out.resize(places.size());
  const Mat3 to_user = base_.frame().rotation().transpose();
  const Vec3 origin = kind == NetWriter::Kind::positions ? base_.frame().origin() : Vec3::Zero();
  for (std::size_t k = 0; k < places.size(); ++k) {
    const NetPlace& p = places[k];
    const NetState& state = states[p.member];
    Vec3 g = state.general[p.entry];
    if (p.boundary != 0) {
      const double apex = p.boundary == 1 ? state.apexes.front() : state.apexes.back();
      g = g + (Vec3(0, 0, apex) - state.axial[p.entry]);
    }
    out[k] = NetWriter::user_point(to_user, origin, g);
  }
}

void Assembly::write_configuration(AssemblyConfiguration& out) const {
  const std::vector<NetState>& states = out.states;
  out.members.resize(members_.size());
  out.closure.assign(members_.size(), ClosureGap{});
  for (std::size_t m = 0; m < members_.size(); ++m) {
    out.members[m].resize(members_[m].topology.vertex_count());
    write_user(m, states[m], out.members[m]);
    if (members_[m].closed) {
      const std::size_t n = states[m].apexes.size() - 1;
      for (std::size_t i = 0; i < members_[m].topology.rows(); ++i) {
        const double gap = (states[m].general[i * n + n - 1] - states[m].general[i * n]).norm();
        if (!(gap <= out.closure[m].value)) out.closure[m] = {gap, i};
      }
    }
  }
}

AssemblyConfiguration Assembly::evaluate(double t) const {
  AssemblyConfiguration out;
  evaluate(t, out);
  return out;
}

const std::vector<std::vector<VertexRef>>& Assembly::shared_vertices() const {
  if (shared_) return *shared_;
  if (members_.size() < 2) {  // only vertices of different members are joined
    shared_.emplace();
    return *shared_;
  }
  // All vertices sorted by x; a sweep joins those of different members closer than eps.
  std::vector<VertexRef> all;
  for (std::size_t m = 0; m < members_.size(); ++m) {
    for (std::size_t v = 0; v < members_[m].reference.size(); ++v) all.push_back({m, v});
  }
  auto position = [&](const VertexRef& r) -> const Vec3& { return members_[r.member].reference[r.vertex]; };
  std::sort(all.begin(), all.end(), [&](const VertexRef& a, const VertexRef& b) { return position(a).x() < position(b).x(); });
  std::vector<std::size_t> parent(all.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const double eps = tolerance::check_relative * model_size_;
  for (std::size_t a = 0; a < all.size(); ++a) {
    for (std::size_t b = a + 1; b < all.size() && position(all[b]).x() - position(all[a]).x() <= eps; ++b) {
      if (all[a].member != all[b].member && (position(all[a]) - position(all[b])).norm() <= eps) {
        parent[find(a)] = find(b);
      }
    }
  }
  std::vector<std::vector<VertexRef>> groups(all.size());
  for (std::size_t a = 0; a < all.size(); ++a) groups[find(a)].push_back(all[a]);
  std::vector<std::vector<VertexRef>> shared;
  for (auto& g : groups) {
    if (g.size() < 2) continue;
    std::sort(g.begin(), g.end(), [](const VertexRef& a, const VertexRef& b) {
      return a.member != b.member ? a.member < b.member : a.vertex < b.vertex;
    });
    shared.push_back(std::move(g));
  }
  std::sort(shared.begin(), shared.end(), [](const auto& a, const auto& b) {
    return a.front().member != b.front().member ? a.front().member < b.front().member
                                                : a.front().vertex < b.front().vertex;
  });
  shared_ = std::move(shared);
  return *shared_;
}

}  // namespace phedra
