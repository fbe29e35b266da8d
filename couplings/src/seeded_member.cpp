#include "phedra/seeded_member.h"

#include "phedra/closed_profile.h"
#include "phedra/errors.h"
#include "phedra/number_format.h"
#include "phedra/parallel_net.h"
#include "phedra/tolerances.h"

#include <cmath>

namespace phedra {
namespace {

void check_heights(const std::vector<double>& z, double scale, const std::string& field) {
  const double eps = tolerance::scaled(tolerance::coincident, scale);
  for (std::size_t j = 0; j + 1 < z.size(); ++j) {
    for (std::size_t k = j + 1; k < z.size() && k <= j + 2; ++k) {
      if (std::abs(z[j] - z[k]) <= eps) {
        throw InvalidInputError(field, "apexes T_" + std::to_string(j) + " and T_" + std::to_string(k) +
                                           " of this member coincide (" + format_number(z[j]) +
                                           "); three consecutive apexes must be pairwise distinct");
      }
    }
  }
}

}  // namespace

SeededMember::SeededMember(const MemberSpec& spec, const NetState& parent, std::size_t parent_columns,
                           const Points& directions, const CanonicalFrame& frame, double scale)
    : seed_(spec.seed), closed_(spec.closed) {
  const std::size_t rows = parent.axial.size() / parent_columns;
  if (seed_.vertex_line + 1 >= parent.apexes.size()) {
    throw InvalidInputError(spec.field, "vertex line " + std::to_string(seed_.vertex_line) +
                                            " does not exist on the parent (it has " +
                                            std::to_string(parent.apexes.size() - 1) + " profile vertices)");
  }
  CanonicalInput input;
  input.directions = directions;
  input.scale = scale;
  input.trajectory.reserve(rows);
  Points general_trajectory;
  general_trajectory.reserve(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    input.trajectory.push_back(parent.axial[i * parent_columns + seed_.vertex_line]);
    general_trajectory.push_back(parent.general[i * parent_columns + seed_.vertex_line]);
  }
  heights_ = {parent.apexes[seed_.first_apex()], parent.apexes[seed_.second_apex()]};
  for (double h : spec.further_heights) heights_.push_back(frame.height_to_canonical(h));
  if (closed_) {
    heights_.push_back(heights_[0]);
    heights_.push_back(heights_[1]);
  }
  if (heights_.size() < 3) throw InvalidInputError(spec.field, "a member needs at least one further apex height");
  check_heights(heights_, scale, spec.field);
  signs_.assign(heights_.size() - 2, spec.sign);
  input.heights = heights_;
  input.signs = signs_;

  try {
    const AxialNet axial = build_axial_net(input);
    const ParallelNet parallel = build_parallel_net(axial, general_trajectory);
    motion_ = NetMotion(axial, parallel, signs_);
    reference_ = {axial.vertices, parallel.vertices, heights_};
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(spec.field, e.what());
  }
  if (closed_) {
    const std::size_t n = motion_.columns();
    for (std::size_t i = 0; i < rows; ++i) {
      const double gap = (reference_.general[i * n + n - 1] - reference_.general[i * n]).norm();
      if (!(gap <= tolerance::check_relative * scale)) {
        throw InvalidInputError(spec.field, "the member's profile does not close at t* (gap " + format_number(gap) +
                                                " at row " + std::to_string(i) + ")");
      }
    }
  }
}

void SeededMember::evaluate(const NetState& parent, std::size_t parent_columns, NetState& out, bool closure) const {
  const std::size_t n = motion_.columns();
  const std::size_t count = closed_ && !closure ? n - 1 : n;  // the columns computed in rows past the first
  const std::size_t rows = motion_.rows();
  const std::size_t k = seed_.vertex_line;
  out.axial.resize(rows * n);
  out.general.resize(rows * n);
  out.apexes.resize(n + 1);
  motion_.complete_first_row(parent.apexes[seed_.first_apex()], parent.apexes[seed_.second_apex()], parent.axial[k],
                             out.apexes.data(), out.axial.data());
  std::copy(out.axial.begin(), out.axial.begin() + n, out.general.begin());
  for (std::size_t i = 1; i < rows; ++i) {
    Vec3* axial = &out.axial[i * n];
    Vec3* general = &out.general[i * n];
    axial[0] = parent.axial[i * parent_columns + k];
    motion_.fill_row(i, out.apexes.data(), axial, count);
    general[0] = parent.general[i * parent_columns + k];
    motion_.advance_general_row(i, axial - n, axial, general - n, general, 1, count);
  }
}

}  // namespace phedra
