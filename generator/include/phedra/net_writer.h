#pragma once
// Writes rows of a general net (canonical frame) into an output grid in the
// user's frame: open nets get their boundary columns (towards S_0 and S_n),
// closed ones their N = n - 1 distinct columns.

#include "phedra/canonical_frame.h"

#include <span>

namespace phedra {

class NetWriter {
 public:
  /// What the rows are: positions, or their rates d/dt (rotated only).
  enum class Kind { positions, rates };
  NetWriter(const CanonicalFrame& frame, bool closed, std::size_t n, std::span<Vec3> out, Kind kind = Kind::positions)
      : to_user_(frame.rotation().transpose()),
        origin_(kind == Kind::positions ? frame.origin() : Vec3::Zero()),
        closed_(closed),
        n_(n),
        out_(out) {}

  /// Output columns per row: n + 2 (open) or n - 1 (closed).
  static std::size_t columns(bool closed, std::size_t n) { return closed ? n - 1 : n + 2; }

  /// Output column c of a row in the canonical frame, from the apexes s[0..n],
  /// the axial row and the general row (n entries each): what write() puts
  /// there before turning it into the user's frame.
  static Vec3 canonical(bool closed, std::size_t n, std::size_t c, const double* s, const Vec3* axial,
                        const Vec3* general) {
    if (closed) return general[c];
    if (c == 0) return general[0] + (Vec3(0, 0, s[0]) - axial[0]);
    if (c == n + 1) return general[n - 1] + (Vec3(0, 0, s[n]) - axial[n - 1]);
    return general[c - 1];
  }
  /// A canonical point (or rate: `origin` zero) in the user's frame: origin +
  /// to_user p, each coordinate's sum left to right. Spelled out, not Eigen's
  /// product, whose order differs between its vectorized and its scalar paths
  /// (the z coordinate is summed right to left with SSE2): the samples evaluated
  /// together (couplings/src/assembly_lanes.cpp) round exactly as this.
  static Vec3 user_point(const Mat3& to_user, const Vec3& origin, const Vec3& p) {
    Vec3 out;
    for (int c = 0; c < 3; ++c) out[c] = origin[c] + ((to_user(c, 0) * p[0] + to_user(c, 1) * p[1]) + to_user(c, 2) * p[2]);
    return out;
  }
  /// Row i from the apexes s[0..n], the axial row and the general row (n entries each).
  void write(std::size_t i, const double* s, const Vec3* axial, const Vec3* general) const {
    if (closed_) {
      Vec3* row = out_.data() + i * (n_ - 1);
      for (std::size_t c = 0; c + 1 < n_; ++c) row[c] = user(general[c]);
      return;
    }
    Vec3* row = out_.data() + i * (n_ + 2);
    row[0] = user(general[0] + (Vec3(0, 0, s[0]) - axial[0]));
    for (std::size_t j = 0; j < n_; ++j) row[j + 1] = user(general[j]);
    row[n_ + 1] = user(general[n_ - 1] + (Vec3(0, 0, s[n_]) - axial[n_ - 1]));
  }

 private:
  Vec3 user(const Vec3& p) const { return user_point(to_user_, origin_, p); }
  Mat3 to_user_;
  Vec3 origin_;
  bool closed_;
  std::size_t n_;
  std::span<Vec3> out_;
};

}  // namespace phedra
