// How far one surface lies from another: the Hausdorff distance between a part and its slimmed
// result, measured in the core so that the CLI and the filters can report it beside the volume
// change and the crease share (shape_metrics.h) without MeshLab.
//
//   SurfaceDistance d = surface_distance(a, b);
//
// Inputs: two surfaces (#V by 3 mm, #F by 3), checked; any faces, open or closed.
// Output (SurfaceDistance): the largest and the mean distance, both ways, from the samples of one
//   surface to the nearest point of the other (mm): its vertices (those of some face: a vertex of
//   no face is no part of the surface), its face centroids and its edge midpoints (samples of
//   zero-area faces too). hausdorff_mm = the larger of the two largest.
// Exact point-to-triangle distances (the closest point on each candidate triangle), the candidates
// from a tree of the other surface's face boxes (face_box_tree.h), so the cost is about
// O((#V + #F) log) rather than O(#V #F). Deterministic; parallel over the samples.
// eval/studies/hausdorff.sh measures the same with MeshLab's filter (its 100,000 samples on faces, edges
// and vertices): the two agree to the sampling's resolution.
#pragma once

#include "core/geometry/surface.h"

namespace slim {

struct SurfaceDistance {
  double a_to_b_max_mm = 0.0, b_to_a_max_mm = 0.0;
  double a_to_b_mean_mm = 0.0, b_to_a_mean_mm = 0.0;
  double hausdorff_mm = 0.0;  // max of the two maxima
};

SurfaceDistance surface_distance(const Surface& a, const Surface& b);

// The Hausdorff distance between a surface and the same mesh moved (b: a's faces, a's vertex count,
// other positions), as surface_distance(a, b).hausdorff_mm, exactly, without the means: each
// sample's own moved copy lies on the other surface, so its distance is at most how far it moved.
// The vertices and the faces (whose samples move at most as far as their corner that moved most)
// are searched both ways from the one that moved most down to the first that moved less than the
// largest distance found, which no later one can exceed; no sample is made or sorted before it is
// needed. Only the samples that moved most are searched (a full search from every sample is far too
// slow on a million-face part: docs/history/speed-earlier.md). Throws std::invalid_argument when b
// is not a's mesh.
double hausdorff_of_moved(const Surface& a, const Surface& b);

}  // namespace slim
