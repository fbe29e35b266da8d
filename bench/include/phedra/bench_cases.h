#pragma once
// The inputs of the benchmarks (issue 5, docs/performance.md): generated, well
// conditioned designs of a chosen size, shared by `phedra bench` and the Google
// Benchmark binary.

#include "phedra/control_polylines.h"
#include "phedra/design.h"

#include <nlohmann/json.hpp>

#include <cstddef>

namespace phedra::bench {

/// A general open P-hedron (profile planes off the axis, all '+' signs) with
/// `profiles` profiles of n + 1 apexes: profiles x (n + 2) vertices. A helical
/// trajectory whose profile planes are turned by a small oscillating angle.
/// With `mixed_signs`, every third sign is '-' (the sigma- ratios then differ
/// from row to row and are stored per vertex).
ControlPolylines general_open_input(std::size_t profiles, std::size_t n, bool mixed_signs = false);

/// The open P-hedron of general_open_input with about `vertices` vertices: 1000
/// a profile from 10^6 vertices on, 100 from 10^4 on, 10 below.
ControlPolylines open_input_with_vertices(std::size_t vertices, bool mixed_signs = false);

/// A 10 x 10 (cells x cells) parallelogram array on a helical trajectory of
/// `segments` segments: every cell face-coupled to its neighbours and
/// edge-sharing with its diagonal ones.
Design parallelogram_array(std::size_t cells, std::size_t segments);

/// An open P-hedron design with about `panels` panels (faces).
/// tests/data/grid-10x10.json's array (cells x cells parallelogram cells on a
/// helix of `segments`, every panel convex): the mechanics' figures (n5b8).
Design mechanics_array(std::size_t cells, std::size_t segments);

Design open_design_with_panels(std::size_t panels);

/// The default preset as it was before issue 13 made it buildable (70 panels,
/// signs +-+-+): 10 bow-ties and a collision at t*; what `phedra repair` of a
/// default-sized design is measured on.
nlohmann::json unbuildable_default_preset();

/// An unbuildable open design with `strips` strips, as a preset: the designer
/// bench's buildable helix (8 apexes, all '+') with apex height 1 moved below
/// height 2, so that every face of the first column is a bow-tie (an edit gone wrong).
nlohmann::json unbuildable_open_preset(std::size_t strips);

/// The designer bench's buildable helix (tests/js/browser.mjs helixPreset): `strips`
/// strips on a third of a helix, profile planes turned by -20 degrees, 8 apexes all '+'.
nlohmann::json designer_helix_preset(std::size_t strips);

/// The browser designer bench's model (tests/js/browser.mjs helixPreset): about
/// `vertices` vertices, sqrt(N) profiles on a third of a helix and as many apex
/// heights in a climbing zigzag; buildable with the default size bounds.
nlohmann::json designer_grid_helix_preset(std::size_t vertices);

}  // namespace phedra::bench
