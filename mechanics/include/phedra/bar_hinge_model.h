#pragma once
// The bar-and-hinge model of a design at one t, with MERLIN2's definitions
// (Liu and Paulino 2017, 2018; Filipov et al. 2017), so that its figures compare
// with the field's codes (docs/design.md, "Mechanics"):
//
// - nodes and panels: model_mesh.h (a triangle panel has no diagonal, no
//   bending hinge, no centre);
// - panels: n4b5 splits each quad along its shorter diagonal (|P0-P2| < |P1-P3|:
//   on 0-2; refused when they differ by 1e-6 relative or less); n5b8 adds a
//   centre node at the diagonals' intersection, four spokes and four bending
//   hinges (spoke c-v_k, wings v_(k-1), v_(k+1)); a panel whose diagonals meet
//   outside it (not convex: a reflex corner or a bow-tie) is refused there;
// - bars: one per distinct edge (panel edge, n4b5 diagonal, n5b8 spoke), EA / L;
// - hinges: a fold hinge for every unordered pair of panels sharing an edge
//   (p (p - 1) / 2 for an edge of p panels), its wings the third nodes of the two
//   triangles at the edge; bending hinges across diagonals or spokes; rotational
//   stiffness k L, L the hinge's length.
//
// The node numbering: the mesh's nodes (model_mesh.h), then the n5b8 centres in
// panel order.

#include "phedra/design.h"
#include "phedra/hinge_angle.h"
#include "phedra/model_mesh.h"

#include <Eigen/SparseCore>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace phedra {

enum class PanelModel { n4b5, n5b8 };
std::string to_string(PanelModel model);
/// "n4b5" or "n5b8"; InvalidInputError("--panels") otherwise.
PanelModel parse_panel_model(const std::string& name);

/// MERLIN2's calibration from a plate material (PrepareData's 'auto' mode):
/// bar areas from each panel's shape, fold and bending stiffness from the
/// plate's bending rigidity D = E T^3 / (12 (1 - nu^2)) (docs/design.md).
struct Material {
  double youngs_modulus = 0.0;  ///< E
  double poisson = 0.0;         ///< nu, in (0, 0.5)
  double thickness = 0.0;       ///< T, model units
  /// L* of the fold stiffness (MERLIN2's LScaleFactor); none: twice the mean fold length.
  std::optional<double> length_scale;
};

struct StiffnessOptions {
  PanelModel panels = PanelModel::n5b8;
  double bar = 1e3;             ///< EA of every bar (MERLIN2's manual mode: 0.1 x 1e4)
  double bend = 0.1;            ///< KB, per unit hinge length
  std::optional<double> fold;   ///< KF, per unit hinge length; none: KB / 10
  std::optional<Material> material;  ///< instead of bar, bend and fold (n5b8 only)
  double fold_value() const { return fold ? *fold : bend / 10.0; }
  /// InvalidInputError naming the option for a value that is not positive and
  /// finite, or a material with n4b5.
  void validate() const;
};

struct Bar {
  std::array<std::size_t, 2> nodes{};
  double length = 0.0;     ///< at the model's t
  double stiffness = 0.0;  ///< EA
};

enum class HingeKind { fold, bend };

struct Hinge {
  std::array<std::size_t, 4> nodes{};  ///< [j k i l]
  HingeKind kind = HingeKind::fold;
  double length = 0.0;     ///< |x_k - x_j| at the model's t
  double stiffness = 0.0;  ///< k per unit length (k L is the spring's)
  /// fold: the two panels (model panel indices, first < second); bend: the panel twice.
  std::array<std::size_t, 2> panels{};
};

class BarHingeModel {
 public:
  /// The model of `design` at the configuration `at` (its t). Throws
  /// InvalidInputError for a collapse it cannot model and for a quad whose
  /// diagonals are equal (n4b5).
  BarHingeModel(const Design& design, const AssemblyConfiguration& at, const StiffnessOptions& options);

  double t() const { return mesh_.t; }
  PanelModel panel_model() const { return panels_model_; }
  std::size_t node_count() const { return positions_.size(); }
  std::size_t corner_node_count() const { return mesh_.positions.size(); }
  const Points& positions() const { return positions_; }
  const std::vector<Bar>& bars() const { return bars_; }
  const std::vector<Hinge>& hinges() const { return hinges_; }
  /// The mesh: its nodes are the model's first nodes; its panels have their centres (n5b8) or splits (n4b5).
  const ModelMesh& mesh() const { return mesh_; }
  const std::vector<ModelPanel>& panels() const { return mesh_.panels; }
  std::size_t fold_count() const { return folds_; }
  std::size_t bend_count() const { return hinges_.size() - folds_; }
  /// Panels of the panel mesh not in the model (walls two cells share, kept once there too).
  std::size_t dropped_faces() const { return mesh_.dropped_faces; }
  std::size_t triangle_panels() const { return mesh_.triangle_panels; }

  /// The nodes' positions in another configuration of the same design
  /// (the centres follow their panels).
  void node_positions(const AssemblyConfiguration& c, Points& out) const;
  /// The nodes' rates from the members' rates (Assembly::evaluate_rate).
  void node_rates(const std::vector<Points>& member_rates, Points& out) const;

  /// The model's triangles (node indices): a quad's two (n4b5) or four around
  /// its centre (n5b8), a triangle panel itself; in panel order.
  std::vector<std::array<std::uint32_t, 3>> triangles() const;

  /// theta of hinge h at the nodes' positions `x`.
  double angle(std::size_t h, const Points& x) const;

  /// The tangent stiffness at rest (no bar force, no moment): sum over bars of
  /// (EA / L) b b^T and over hinges of k L grad(theta) grad(theta)^T, 3 x nodes square.
  Eigen::SparseMatrix<double> stiffness() const;
  /// Its upper triangle (diagonal included): what the eigen-solvers read
  /// (stiffness_modes.h), half the memory and the assembly of the whole.
  Eigen::SparseMatrix<double> stiffness_upper() const;

 private:
  /// InvalidInputError (--bar, or --thickness with a material) when the
  /// stiffnesses span more than 1e12 or leave [1e-100, 1e100].
  void check_stiffness_spread(const StiffnessOptions& options) const;

  /// The centres follow their panels: out's first nodes are set.
  void place_centres(Points& out) const;
  ModelMesh mesh_;
  Points positions_;  ///< the mesh's nodes, then the centres
  std::vector<Bar> bars_;
  std::vector<Hinge> hinges_;
  std::size_t folds_ = 0;
  PanelModel panels_model_ = PanelModel::n5b8;
};

/// The nodes of a hinge in `x`.
inline HingeNodes hinge_nodes(const Hinge& h, const Points& x) {
  return {x[h.nodes[0]], x[h.nodes[1]], x[h.nodes[2]], x[h.nodes[3]]};
}

}  // namespace phedra
