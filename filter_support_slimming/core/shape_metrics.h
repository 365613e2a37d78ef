// What a deformation cost the shape: volume change and new creases, result against input.
//
// Inputs:
//   input   #V by 3 positions and #F by 3 faces: the shape before (mm)
//   result  the same faces (identical F) with moved positions: the shape after (mm)
//   options crease threshold (below)
// Outputs (ShapeChange):
//   volume_change_pct  100 * (V_result / V_input - 1), V the signed enclosed volume
//                      (surface.h); 0 when the input encloses no volume (then
//                      volume_defined is false)
//   crease_share_pct   over the interior manifold edges (exactly two faces, running along the
//                      edge in opposite directions, neither of zero area in either shape): the
//                      length-weighted share, in %, of edges whose signed dihedral angle
//                      changes by more than `crease_threshold_deg` from input to result
//   crease_p99_deg     the length-weighted 99th percentile of that change (degrees)
//   max_crease_deg     the largest change (degrees)
//   interior_edges     how many edges were measured
//
// The dihedral angle of an edge is the angle between its two faces' normals, signed: positive
// where the surface bends outward (convex), negative where it bends inward. The change is
// |angle_result - angle_input| wrapped into [0, 180], so a convex edge that turns concave counts
// in full (unsigned angles would call a 20° ridge folded into a 20° valley "unchanged"). Edge lengths
// are the input's: the weight is what the designer drew, not what the deformation made of it.
//
// A rigid motion or a uniform scale changes no dihedral angle (crease share 0); a scale by s
// changes the volume by 100 (s^3 - 1) %. Cost: O(#F log #F) (one sort of the edges).
// Throws std::invalid_argument when the two surfaces do not share F, have different vertex
// counts, or fail check_surface().
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/surface.h"

namespace slim {

struct ShapeChangeOptions {
  double crease_threshold_deg = 10.0;  // a dihedral change above this is a new crease, degrees
};

struct ShapeChange {
  double volume_input = 0.0;       // mm³, signed enclosed volume of the input
  double volume_result = 0.0;      // mm³
  bool volume_defined = false;     // the input encloses a non-zero volume
  double volume_change_pct = 0.0;  // 100 * (volume_result / volume_input - 1)
  double crease_share_pct = 0.0;   // % of interior manifold edge length
  double crease_p99_deg = 0.0;     // length-weighted 99th percentile of the dihedral change
  double max_crease_deg = 0.0;     // largest dihedral change
  Eigen::Index interior_edges = 0; // interior manifold edges measured
};

ShapeChange shape_change(const Surface& input, const Surface& result, const ShapeChangeOptions& options = {});

// Per interior manifold edge of `s`: the two vertices (lower id first), its two faces (the one
// running from the lower to the higher vertex first) and its signed dihedral angle (degrees).
// Edges on a zero-area face are left out. Used by shape_change() and its tests.
struct DihedralEdge {
  int v0, v1, f0, f1;
  double angle_deg;
};
std::vector<DihedralEdge> dihedral_edges(const Surface& s);

}  // namespace slim
