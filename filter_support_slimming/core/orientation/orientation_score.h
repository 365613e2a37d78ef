// The orientation search's scoring (orientation.h): a table of the surface's faces prepared once,
// and the score of any number of print directions, swept fast or computed exactly.
//
//   OrientationGeometry g = orientation_geometry(surface, options, with_hull, inside_out);
//   std::vector<double> s = sweep_scores(g, directions);       // fast; the search's sweep
//   OrientationCandidate c = exact_score(g, d, "origin");      // the score as orientation.h defines it
//
// Inputs:  a checked surface (#V by 3 mm, #F by 3), OrientationOptions (alpha_max, plate tolerance,
//          contact bonus), and whether to build the convex hull (the sweep's plate walk and the
//          resting-facet candidates need it; a single exact score does not).
// Outputs: OrientationGeometry below: the faces with a positive area, in normal-bin order, as
//          structure-of-arrays relative to the vertices' centroid (heights lose no digits far from
//          the origin); the bins; the hull and its vertex graph; the size, tau and tolerances used.
//          sweep_scores: one score per direction (mm³, lower is better), summed bin by bin: a bin
//          wholly beyond the threshold adds its shadow in closed form, a wholly safe one adds
//          nothing, only the bins straddling the threshold are visited face by face; the plate
//          height comes from a walk on the hull's vertices. exact_score: the plate from every
//          vertex and the plate rule face by face (overhang.h: face_support), so its shadow volume
//          equals analyse_overhang's for the same direction.
// Errors: orientation_geometry throws std::invalid_argument for no faces, zero extent or area,
// faces that are not consistently oriented, or options out of range; inside_out is set for a
// closed mesh whose normals all point inwards (its normals are then turned over).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/checked_surface.h"
#include "core/geometry/convex_hull.h"
#include "core/orientation/orientation.h"

namespace slim {

// Faces whose normals fall in one cube-map cell, with what the sweep needs to add them up at once.
// For a direction d, let theta be the angle between d and the bin's axis and beta = acos(-tau) the
// angle from d beyond which a normal is risky. Every face of the bin lies within `radius` of the
// axis, so theta > beta + radius makes them all risky and theta < beta - radius all safe; only
// the bins in between (a band around the circle of the threshold) are visited face by face. An
// all-risky bin adds
//   sum of area * -(n·d) * (c·d - plate) = -d^T (sum of area * n c^T) d + plate * (sum of area * n)·d.
struct NormalBin {
  Eigen::Index begin = 0, end = 0;  // its faces, in Geometry's face order
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit area-weighted mean normal
  Eigen::Matrix3d normal_centroid = Eigen::Matrix3d::Zero();  // sum of area * n c^T
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();       // sum of area * n
  double area = 0.0;
  double cos_all_risky = -2.0;  // axis·d below this: every face risky (-2: never)
  double cos_all_safe = 2.0;    // axis·d above this: every face safe (2: never)
  double cos_near_plate = 2.0;  // -axis·d above this: visit face by face
};

// Everything per face that a score needs, computed once, as structure-of-arrays: the faces with a
// positive area (the others add nothing to any score), ordered by normal bin, positions relative
// to the vertices' centroid so that heights lose no digits for a part far from the origin.
struct OrientationGeometry {
  Points V;  // #V by 3, relative to `centre`
  Triangles F;  // the kept faces, in bin order
  Eigen::Vector3d centre;
  Eigen::Index faces = 0;
  std::vector<double> nx, ny, nz, cx, cy, cz, area;
  std::vector<NormalBin> bins;
  Points extreme;  // the convex hull's vertices (relative), or every vertex when there is no hull
  ConvexHull hull;
  // The hull's vertex graph (CSR over the rows of `extreme`), and anchor directions with their
  // lowest hull vertex, where the walks of sweep_plate() start.
  std::vector<int> adjacency_start, adjacency;
  Eigen::Matrix3Xd anchors;
  std::vector<int> anchor_lowest;
  double size = 0.0, total_area = 0.0, tau = 0.0, bonus_height = 0.0;
  std::optional<double> tolerance;  // mm, the plate rule's; none: no face rests on the plate
};

// The cell of a unit vector on a cube map with R by R cells on each of the cube's six faces.
int cube_cell(const Eigen::Vector3d& n, int R);

OrientationGeometry orientation_geometry(const CheckedSurface& surface, const OrientationOptions& options, bool with_hull,
                                         bool& inside_out);
std::vector<double> sweep_scores(const OrientationGeometry& g, const std::vector<Eigen::Vector3d>& directions);
OrientationCandidate exact_score(const OrientationGeometry& g, const Eigen::Vector3d& d, const std::string& origin);

}  // namespace slim
