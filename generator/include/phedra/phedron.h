#pragma once
// A general P-hedron from three control polylines: construction (everything
// that does not depend on t) and its isometric deformation evaluate(t). Open
// P-hedra have boundary columns; inputs with a closed profile (closed_profile.h)
// are tubes with cyclic columns.

#include "phedra/axial_net.h"
#include "phedra/canonical_frame.h"
#include "phedra/control_polylines.h"
#include "phedra/flexion_interval.h"
#include "phedra/grid_topology.h"
#include "phedra/linkage.h"
#include "phedra/net_motion.h"
#include "phedra/parallel_net.h"
#include "phedra/strip_chain.h"

#include <span>
#include <string>
#include <vector>

namespace phedra {

/// The largest gap |V_{i,N}(t) - V_{i,0}(t)| of a closed profile, and its row.
struct ClosureGap {
  double value = 0.0;
  std::size_t row = 0;
};

class PHedron {
 public:
  /// Validates the input (validate()) and constructs the axial net, the parallel
  /// net, the motion and the flexion interval. Throws InvalidInputError (naming
  /// the field and index) for every violated assumption of MATH.md, and for a
  /// closed profile that does not close at t*.
  explicit PHedron(ControlPolylines input);

  const ControlPolylines& input() const { return input_; }
  /// Open: (m + 1) rows by (n + 2) columns: boundary S_0, V_{i,0..n-1}, boundary S_n.
  /// Closed: (m + 1) rows by N = n - 1 cyclic columns V_{i,0..N-1}.
  const GridTopology& topology() const { return topology_; }
  bool closed() const { return closed_; }
  std::size_t vertex_count() const { return topology_.vertex_count(); }
  /// n: vertices per profile of the construction (a closed profile's last one repeats its first).
  std::size_t profile_vertex_count() const { return motion_.columns(); }

  /// The motion parameter t is the axis coordinate (user frame) of the moving
  /// apex: S_0 in case (a), S_1 in case (b).
  MotionCase motion_case() const { return linkage_.motion_case(); }
  double t_star() const { return t_star_; }
  /// [t_lambda, t_mu] (user t) with the strip that causes each end.
  const FlexionInterval& flexion_interval() const { return interval_; }
  /// Searches the flexion interval again (what the constructor stores in
  /// flexion_interval()); for benchmarks.
  FlexionInterval search_flexion_interval() const;
  /// t_lambda + fraction * (t_mu - t_lambda); fraction in [0, 1] (InvalidInputError otherwise).
  double t_at_fraction(double fraction) const;

  /// The constructed net at t* (user frame, topology order), before any motion.
  const Points& reference() const { return reference_; }
  /// Bounding-box diagonal of reference(): the length scale of every check.
  double model_size() const { return model_size_; }

  /// Vertex positions at t in the user frame (topology order); `out` has
  /// vertex_count() entries. The motion keeps the axis, the plane pi_0 and the
  /// axis coordinate of V_{0,0} fixed. For a closed profile, `gap` (if given)
  /// gets the largest closure gap. Throws OutOfIntervalError outside the
  /// flexion interval.
  void evaluate(double t, std::span<Vec3> out, ClosureGap* gap = nullptr) const;
  Points evaluate(double t) const;

  /// The motion on another branch: strips whose `flipped` entry is true (index =
  /// strip, size m + 1, entry 0 unused) take the mirror of their input branch.
  /// The flexion interval is the same on every branch (a strip's margin depends
  /// on the apexes alone), so these are the other passes of the configuration
  /// curve (configuration_cycle()).
  void evaluate(double t, const std::vector<bool>& flipped, std::span<Vec3> out, ClosureGap* gap = nullptr) const;

  /// The whole configuration curve through the flexion limits (paper, Remark 3):
  /// from t* to t_mu on the input branch; at a limit caused by strip i >= 1, strip
  /// i switches to its mirror branch and t runs back across the interval, and so
  /// on until the input branch is back at t*. A limit of the linkage L_0 (V_{0,0}
  /// on the axis) cannot be passed: the curve stops there and is not closed.
  struct Pass {
    double from = 0.0, to = 0.0;    ///< t runs from `from` to `to`
    std::vector<bool> flipped;      ///< the branch (as for evaluate)
    std::size_t switched = 0;       ///< the strip switched at the start of this pass (0: none)
  };
  struct ConfigurationCycle {
    std::vector<Pass> passes;
    bool closed = false;            ///< back at t* on the input branch
    std::string stop;               ///< why it is not closed
  };
  ConfigurationCycle configuration_cycle() const;

  /// The axial and the general net at t in the canonical frame (rows x n, row-major,
  /// no boundary columns) and the apex heights s_0..s_n (canonical): what the
  /// members of an assembly are seeded on.
  /// `flipped` (optional): the branch, as for evaluate.
  void evaluate_canonical(double t, Points& axial, Points& general, std::vector<double>& apexes,
                          const std::vector<bool>* flipped = nullptr) const;

  /// The canonical state at t (as evaluate_canonical) and its exact rate d/dt
  /// (MATH.md section 4 differentiated: the linkage L_0 and the strip chain in
  /// closed form, the rest by the same linear recursions). Throws
  /// OutOfIntervalError outside the flexion interval. Returns false at a flexion
  /// limit (t_lambda or t_mu), where the rate is infinite (`state` is complete, `rate` is not).
  bool evaluate_canonical_rate(double t, NetState& state, NetState& rate,
                               const std::vector<bool>* flipped = nullptr) const;

  /// Heights <S_j(t), axis> (user frame) of the apexes S_0..S_n at t.
  std::vector<double> apex_heights(double t) const;

  /// The margin of the motion at t (negative where it is not real), and the strip
  /// that has the smallest one.
  StripMargin margin(double t) const;
  /// The margin of one strip at t (0: the linkage L_0), in O(1).
  double strip_margin(double t, std::size_t strip) const;

  const CanonicalFrame& frame() const { return frame_; }
  /// The input in the canonical frame.
  const CanonicalInput& canonical_input() const { return canonical_; }
  /// The axial and the parallel net at t* (canonical frame), rebuilt on each call:
  /// a P-hedron keeps only reference() and the constants of its motion.
  AxialNet axial_net() const { return build_axial_net(canonical_); }
  ParallelNet parallel_net() const { return build_parallel_net(axial_net(), canonical_.trajectory); }
  const NetMotion& motion() const { return motion_; }

 private:
  double canonical_t(double t) const { return frame_.height_to_canonical(t); }
  StripMargin canonical_margin(double tc) const;
  /// S_0, S_1, V_{0,0} at t (OutOfIntervalError outside the flexion interval).
  LinkageStart start_at(double t) const;
  void evaluate_on(double t, const std::vector<bool>* flipped, std::span<Vec3> out, ClosureGap* gap) const;
  /// V_{i,0} from V_{i-1,0} = previous and the apexes s[0], s[1] at t (Error(internal) if not real).
  void advance_column(std::size_t i, double t, const double* s, const Vec3& previous, Vec3& out,
                      const std::vector<bool>* flipped = nullptr) const;
  /// Runs the motion at t row by row: sink(i, apexes, axial_row, general_row), canonical frame.
  template <class RowSink>
  void run_rows(double t, const std::vector<bool>* flipped, RowSink&& sink) const;

  ControlPolylines input_;
  CanonicalFrame frame_;
  CanonicalInput canonical_;
  NetMotion motion_;
  Linkage linkage_;
  StripChain chain_;
  bool closed_ = false;
  GridTopology topology_;
  /// When every sign is '+' (NetMotion::uniform): row i of the output is row i - 1
  /// plus these coefficients times A_{i,0} - A_{i-1,0}, a row of the output
  /// (width entries) each: q_{i,j} alpha_j, and for an open P-hedron's boundary
  /// columns q_{i,0} - 1 and (q_{i,n-1} - 1) alpha_{n-1}. Empty otherwise.
  std::vector<double> row_coefficients_;
  void compute_row_coefficients();
  Points reference_;
  double model_size_ = 0.0;
  double t_star_ = 0.0;
  FlexionInterval interval_;
};

}  // namespace phedra
