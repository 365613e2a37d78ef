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
// changes the volume by 100 (s^3 - 1) %. Cost: O(#F log #F) (one sort of the edges; CreaseMeter
// below sorts once for many results).
// Throws std::invalid_argument when the two surfaces do not share F, have different vertex
// counts, or fail check_surface().
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

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

// Per interior manifold edge of `s`: the two vertices (lower id first), its two faces (the one
// running from the lower to the higher vertex first) and its signed dihedral angle (degrees).
// Edges on a zero-area face are left out. Used by shape_change() and its tests.
struct DihedralEdge {
  int v0, v1, f0, f1;
  double angle_deg;
};
std::vector<DihedralEdge> dihedral_edges(const Surface& s);

ShapeChange shape_change(const Surface& input, const Surface& result, const ShapeChangeOptions& options = {});

// The crease share of many results of one input, measured again and again (the optimizer's check
// on every iterate, then its result's figures): the input's interior manifold edges, their lengths
// and dihedral angles, and its volume, are found once; share_pct() then costs O(#V + #F + #E), on
// the OpenMP threads; measure() adds the result's volume and the percentile's partition of the
// edges' changes.
//   CreaseMeter meter(input, options);     // input as for shape_change
//   meter.measure(result_V, out);           // #V by 3 (mm), the input's faces: fills all of out
//                                           // as shape_change() does (it is that call's meter)
//   meter.share_pct(result_V)               // crease_share_pct alone (%), the same value but
//                                           // for an edge within rounding of the threshold
//                                           // (it reuses the meter's buffers: one thread at a
//                                           // time per meter)
// Throws std::invalid_argument as shape_change() does (a bad threshold, a result of another size).
class CreaseMeter {
 public:
  explicit CreaseMeter(const Surface& input, const ShapeChangeOptions& options = {});
  void measure(const Points& result_V, ShapeChange& out) const;
  double share_pct(const Points& result_V) const;

 private:
  // The change of each measured edge's angle; false for an edge a result's zero-area face drops.
  void changes(const Surface& result, std::vector<double>& change, std::vector<char>& measured) const;
  Triangles F_;
  Eigen::Index vertices_;
  ShapeChangeOptions options_;
  std::vector<DihedralEdge> edges_;  // the input's, with their angles
  std::vector<double> length_;       // the input's edge lengths (mm)
  std::vector<double> cos_in_, sin_in_;  // of the input's angles
  double volume_input_;              // mm³, signed
  // share_pct's buffers, kept from call to call: one meter serves one thread at a time.
  using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  mutable RowPoints cross_;
  mutable std::vector<char> state_;
};


}  // namespace slim
