// Whether a pose stands on the plate by itself: its footprint and where its weight falls.
//
//   const Eigen::Vector3d c = centre_of_mass(surface);
//   const PoseRest rest = pose_rest(surface.V, direction, tolerance_mm, c);
//
// Inputs:  the surface (#V by 3 positions in mm, #F by 3 outward faces) in any frame; a print
//          direction d (non-zero; normalised here) in that frame; the plate tolerance (mm, >= 0):
//          the vertices within it of the lowest one along d touch the plate; the centre of mass in
//          the same frame.
// Outputs: centre_of_mass: the centroid of the enclosed solid for a closed surface (no open edge,
//          a non-zero volume), of its area otherwise (a scan with holes: its shell). mm.
//          PoseRest: the footprint, the convex hull of the touching vertices in the plane
//          perpendicular to d (its area in mm², 0 for a point or an edge), and `stable`: the
//          centre of mass, projected along d, lies inside the footprint, off its border by at
//          least 1e-6 of the part's size. A part balanced on a point or an edge is never stable;
//          one resting on a face or on three feet around its weight is.
//
// Why: the support model sees only the support a pose needs. A slicer prints a pose balanced on a
// point as readily, but the part may then tip or wobble as it grows; among poses of about the same
// support, one that stands by itself is the better print (orientation.h, the final choice).
#pragma once

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

struct PoseRest {
  double footprint_mm2 = 0.0;  // area of the convex hull of the vertices touching the plate
  bool stable = false;         // the centre of mass lies over the footprint
};

Eigen::Vector3d centre_of_mass(const Surface& surface);

PoseRest pose_rest(const Points& V, const Eigen::Vector3d& direction, double tolerance_mm,
                   const Eigen::Vector3d& centre_of_mass);

}  // namespace slim
