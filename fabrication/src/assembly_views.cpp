// Small 3D views of the assembly as it grows (cut_sheet_parts.h: assembly_views).

#include "cut_sheet_parts.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

namespace phedra::sheets {
namespace {

/// Screen axes and a depth for an oblique view of the points: from above the
/// plane of their two largest spreads, turned 30 degrees about its normal and
/// tilted 35 degrees towards it (so that tubes show their walls, sheets their
/// folds).
struct ViewFrame {
  Vec3 centre, right, up, towards;  ///< towards: from the model to the eye
  Vec2 screen(const Vec3& p) const { return Vec2(right.dot(p - centre), up.dot(p - centre)); }
  double depth(const Vec3& p) const { return towards.dot(p - centre); }
};

ViewFrame view_of(const Points& x) {
  ViewFrame v;
  v.centre = Vec3::Zero();
  for (const Vec3& p : x) v.centre += p;
  v.centre /= static_cast<double>(std::max<std::size_t>(1, x.size()));
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : x) covariance += (p - v.centre) * (p - v.centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Vec3 e1 = solver.eigenvectors().col(2), e2 = solver.eigenvectors().col(1), e3 = e1.cross(e2);
  const double azimuth = 30.0 * M_PI / 180.0, elevation = 55.0 * M_PI / 180.0;
  const Vec3 horizontal = std::cos(azimuth) * e1 + std::sin(azimuth) * e2;
  v.towards = (std::cos(elevation) * horizontal + std::sin(elevation) * e3).normalized();
  v.right = (-std::sin(azimuth) * e1 + std::cos(azimuth) * e2).normalized();
  v.up = v.towards.cross(v.right);
  return v;
}

}  // namespace

std::vector<SheetPage> assembly_views(const CutSheets& s, const AssemblyMesh& mesh, const Points& x) {
  // The step that joins each panel (its piece's number, the first piece when a
  // wall is in two cells' pieces); panels on no piece: never.
  std::map<std::size_t, std::size_t> step_of_panel;
  for (const Piece& piece : s.pieces) {
    for (const PiecePanel& p : piece.panels) step_of_panel.emplace(p.panel, piece.number);
  }
  const std::size_t steps = s.pieces.size();
  if (steps == 0 || mesh.faces.empty()) return {};
  const ViewFrame view = view_of(x);
  struct Face {
    Polygon2 outline;
    double depth = 0.0;
    std::size_t step = std::numeric_limits<std::size_t>::max();
  };
  std::vector<Face> faces;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    Face face;
    Vec3 centroid = Vec3::Zero();
    std::size_t corners = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t v = mesh.faces[f][k];
      if (k > 0 && v == mesh.faces[f][k - 1]) continue;  // a triangle's repeated corner
      face.outline.push_back(view.screen(x[v]));
      centroid += x[v];
      ++corners;
      lo = lo.cwiseMin(face.outline.back());
      hi = hi.cwiseMax(face.outline.back());
    }
    face.depth = view.depth(centroid / static_cast<double>(corners));
    const auto found = step_of_panel.find(f);
    if (found != step_of_panel.end()) face.step = found->second;
    faces.push_back(std::move(face));
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.depth < b.depth; });
  // The picture's long side along the cells' long side (they are wider than tall):
  // the projected points turned so that their largest spread runs across.
  {
    Vec2 mean = Vec2::Zero();
    std::size_t count = 0;
    for (const Face& face : faces) {
      for (const Vec2& p : face.outline) mean += p, ++count;
    }
    mean /= static_cast<double>(std::max<std::size_t>(1, count));
    Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
    for (const Face& face : faces) {
      for (const Vec2& p : face.outline) spread += (p - mean) * (p - mean).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> principal(spread);
    const Vec2 along = principal.eigenvectors().col(1);
    const Eigen::Matrix2d turn = (Eigen::Matrix2d() << along.x(), along.y(), -along.y(), along.x()).finished();
    lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (Face& face : faces) {
      for (Vec2& p : face.outline) {
        p = turn * (p - mean);
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      }
    }
  }

  // Up to 12 views on the page, each after a group of pieces, in the grid (1 to
  // 4 across) that draws them largest: a long, flat model in fewer columns.
  const double m = 10.0, top = s.page.y() - m;
  const std::size_t views = std::min<std::size_t>(steps, 12);
  const double first_top = top - 12.0, caption = 6.0;
  const Vec2 extent = (hi - lo).cwiseMax(Vec2::Constant(1e-12));
  std::size_t across = 1;
  double cell_w = 0.0, cell_h = 0.0, scale = 0.0;
  for (std::size_t columns = 1; columns <= 4; ++columns) {
    const std::size_t rows = (views + columns - 1) / columns;
    const double w = (s.page.x() - 2.0 * m) / static_cast<double>(columns);
    const double h = (first_top - m) / static_cast<double>(rows);
    if (h < caption + 10.0) continue;
    const double fits = 0.92 * std::min((w - 2.0) / extent.x(), (h - caption - 2.0) / extent.y());
    if (fits > scale) across = columns, cell_w = w, cell_h = h, scale = fits;
  }
  SheetPage page;
  add_text(page, s.name + " - assembly in views", Vec2(m, top - 4.0), 4.0, TextRole::title);
  const std::string note = "After each group of pieces: joined grey, the group orange (drawn over the rest, to show where it goes), the rest white; at t*.";
  add_text(page, note, Vec2(m, top - 10.0), std::min(2.2, 2.2 * (s.page.x() - 2.0 * m) / text_width(note, 2.2)), TextRole::note);
  std::size_t from = 1;
  for (std::size_t k = 0; k < views; ++k) {
    const std::size_t to = (steps * (k + 1) + views - 1) / views;  // pieces from..to join in view k
    const double left = m + static_cast<double>(k % across) * cell_w;
    const double cell_top = first_top - static_cast<double>(k / across) * cell_h;
    const Vec2 origin(left + 0.5 * cell_w, cell_top - caption - 0.5 * (cell_h - caption));
    // The rest first, then what is joined (each far to near), then the group on
    // top of everything: the new pieces show where they go even behind others.
    for (const FillStyle style : {FillStyle::view_later, FillStyle::view_joined, FillStyle::view_added}) {
      for (const Face& face : faces) {
        const FillStyle own = face.step < from ? FillStyle::view_joined : face.step <= to ? FillStyle::view_added : FillStyle::view_later;
        if (own != style) continue;
        SheetFill fill{{}, own, std::nullopt};
        for (const Vec2& p : face.outline) fill.outline.push_back(origin + scale * (p - 0.5 * (lo + hi)));
        page.fills.push_back(std::move(fill));
      }
    }
    const std::string what = from == to ? "piece " + std::to_string(to) : "pieces " + std::to_string(from) + "-" + std::to_string(to);
    add_text(page, (k == 0 ? "" : "+ ") + what, Vec2(left + 1.0, cell_top - 3.0), 2.4, TextRole::legend);
    from = to + 1;
  }
  return {page};
}

}  // namespace phedra::sheets
