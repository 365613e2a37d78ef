// Convex hull of a point set in 3D (Quickhull), for the orientation search (resting facets, the
// extreme points the plate walks on) and for the minimal rotation (the hull edges of a patch's
// normals: the pairs of boundary circles that can cross at a feasible point, min_rotation.h).
//
// In:  P        #P by 3 points, in any units.
//      options  eps, a tolerance in P's units, and how near-zero orientation tests are read:
//        tolerant (default)  a point within eps of a facet's plane counts as on the facet, not
//                            outside it, and is dropped: a flat side tessellated into many
//                            coplanar triangles keeps only its corners;
//        strict              every point must be a hull vertex (e.g. distinct unit vectors), and
//                            any orientation test whose value (the point's height times the
//                            facet's doubled area: 6 x the tetrahedron's volume) is within eps of
//                            zero makes the construction fail, because its sign cannot be trusted.
// Out: ConvexHull::facets      #H triangles, indices into P, counter-clockwise seen from outside
//      ConvexHull::normals     #H by 3 unit outward normals
//      ConvexHull::areas       #H facet areas, in squared units
//      ConvexHull::vertices    the indices into P the facets use, ascending
//      ConvexHull::neighbours  per facet, the facet across each edge v[e] -> v[e + 1]
//      hull_edges(hull)        every edge once, i < j, with the third vertices k and l of the two
//                              facets along it
//
// Returns false, leaving the hull empty, when the points are flat or collinear within eps, when a
// strict test is too close to zero, or when rounding makes the construction inconsistent (a
// horizon that is not one loop). The hull only ever serves as an aid, so a caller falls back
// rather than fails. Deterministic: the same points give the same hull. Expected O(n log n):
// each facet's farthest outside point is added next (Quickhull), which keeps the facets large and
// well shaped and the eps tests trustworthy.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

struct ConvexHull {
  std::vector<std::array<int, 3>> facets;
  Points normals;
  Eigen::VectorXd areas;
  std::vector<int> vertices;
  std::vector<std::array<int, 3>> neighbours;
};

struct ConvexHullOptions {
  double eps = 0.0;     // see above; >= 0
  bool strict = false;  // tolerant by default
};

bool convex_hull(const Points& P, const ConvexHullOptions& options, ConvexHull& hull);
// Tolerant, with the given eps.
bool convex_hull(const Points& P, double eps, ConvexHull& hull);

struct HullEdge {
  int i, j;  // the edge, i < j
  int k, l;  // the third vertices of its two facets
};
std::vector<HullEdge> hull_edges(const ConvexHull& hull);

}  // namespace slim
