// Convex hull of a point set in 3D (Quickhull).
//
// In:  P    #P by 3 points, in any units.
//      eps  a distance in P's units: a point within eps of a facet's plane counts as on the
//           facet, not outside it. Points on or within eps of the hull are dropped, so a flat
//           side tessellated into many coplanar triangles keeps only its corners.
// Out: ConvexHull::facets    #H triangles, indices into P, counter-clockwise seen from outside
//      ConvexHull::normals   #H by 3 unit outward normals
//      ConvexHull::areas     #H facet areas, in squared units
//      ConvexHull::vertices  the indices into P the facets use, ascending
//      ConvexHull::neighbours  per facet, the facet across each edge v[e] -> v[e + 1]
//
// Returns false, leaving the hull empty, when the points are flat or collinear within eps or
// when rounding makes the construction inconsistent (a horizon that is not one loop). The hull
// only ever serves as an aid (candidate directions, a small set of extreme points), so a caller
// falls back rather than fails. Deterministic: the same points give the same hull.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/surface.h"

namespace slim {

struct ConvexHull {
  std::vector<std::array<int, 3>> facets;
  Points normals;
  Eigen::VectorXd areas;
  std::vector<int> vertices;
  std::vector<std::array<int, 3>> neighbours;
};

bool convex_hull(const Points& P, double eps, ConvexHull& hull);

}  // namespace slim
