#pragma once
// Whether two closed solids (plates, knuckles, pins) cut into each other: the
// deepest crossing of their surfaces' triangles. The broad phase is each
// solid's oriented box (its longest edge and its largest face give the axes):
// only the triangles of one that reach into the other's box are paired, and a
// pair is tested only when their boxes in the first solid's frame overlap. Long
// thin solids lying askew (pins, the knuckles of hinges meeting at a vertex)
// then pair a few triangles, where world-aligned boxes paired nearly all of
// them. Exact: a crossing's triangles lie in both boxes.

#include "phedra/box_tree.h"
#include "phedra/thick_plates.h"

namespace phedra {

/// A solid with its world box and its oriented box (computed once a configuration).
struct OrientedSolid {
  const Solid* solid = nullptr;
  Box box;      ///< world-aligned
  Mat3 axes;    ///< rows: the oriented box's unit axes
  Box local;    ///< the solid's extent along them
};
OrientedSolid orient(const Solid& solid);

/// The deepest crossing of a's and b's triangles (triangle_penetration), 0 when
/// none crosses; the search stops at the first deeper than `enough`.
double solids_penetration(const OrientedSolid& a, const OrientedSolid& b, double enough);

/// The distance between a's and b's surfaces when it is under `within` (0 when
/// they touch or cross), else `within`: the boxes grown by it first. Parts
/// printed in place must keep a clearance apart.
double solids_gap(const OrientedSolid& a, const OrientedSolid& b, double within);

}  // namespace phedra
