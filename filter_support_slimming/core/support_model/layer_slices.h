// The part's slices as a slicer cuts them: closed contours at given heights, with the open chains
// that holes in the mesh leave either closed across small gaps or dropped.
//
//   std::vector<LayerSlice> slices = slice_layers(surface, adjacency, heights, max_gap);
//
// Inputs
//   surface    #V by 3 positions (mm), #F by 3 faces sharing their vertices, counter-clockwise seen
//              from outside. It may be open (edges used by one face: a hole), non-manifold, or have
//              faces turned over: that is what this is for.
//   adjacency  the faces' adjacency (face_adjacency.h) of surface's faces.
//   heights    #H slice heights (mm, any order).
//   max_gap    mm, >= 0: open chains whose ends lie closer than this are joined (PrusaSlicer 2.5:
//              2 mm, a constant of its TriangleMeshSlicer).
// Output: per height, a LayerSlice:
//   loops    closed contours (the last point joins the first), material on their left: counter-
//            clockwise around material, clockwise around holes, as the faces' sides say. The
//            slice's solid is where they wind (nonzero rule).
//   dropped  the open chains left over, from one end to the other, material on their left.
//
// How the slicer does it (PrusaSlicer 2.5, TriangleMeshSlicer.cpp, read from its sources): every
// face cut at the height gives a segment from the edge it enters by to the edge it leaves by (a
// vertex exactly at the height counts as above it, so a segment never ends on a vertex); segments
// chain through the faces' shared edges. On a closed mesh every chain closes. At a hole (an edge
// with no twin, a non-manifold or turned edge) a chain stops; then, longest chain first, each open
// chain's end is joined to the nearest start of another within max_gap, or the chain is closed on
// itself when its own start lies within max_gap (and, when another start is farther, the gap is
// under 0.3 of its length); a second round may join chains end to end, reversing one, and turns a
// loop so patched counter-clockwise. What stays open is dropped: the slicer prints nothing of it,
// so a hole wider than max_gap empties the slice around it.
//
// Cost: O(#F + the segments) plus, per height, the open chains squared (a few). Heights run in
// parallel (OpenMP), each in a fixed order: the result does not depend on the thread count.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

class FaceAdjacency;

using Polyline2 = std::vector<Eigen::Vector2d>;

struct LayerSlice {
  std::vector<Polyline2> loops;
  std::vector<Polyline2> dropped;
};

std::vector<LayerSlice> slice_layers(const Surface& surface, const FaceAdjacency& adjacency,
                                     const std::vector<double>& heights, double max_gap);

}  // namespace slim
