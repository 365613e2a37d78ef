// How tall a support column each overhang needs: the height of a face above whatever its support
// would stand on, and the support it costs. The optimizer spends its turns on the overhangs that
// cost most (costly_overhangs.h): a face just above the plate or just above the part below needs
// a short column, one high above the plate a tall one.
//
//   Eigen::VectorXd h = column_heights(surface, d, faces);
//
// Inputs
//   surface  #V by 3 positions (mm), #F by 3 faces (indices checked by the caller).
//   d        the print direction (unit).
//   faces    #F flags: the faces to measure (the others get 0).
// Output: #F heights (mm). For a flagged face: the distance along -d from its centroid down to
//   the nearest point below it where the vertical line through the centroid crosses another face
//   of the surface (the part below it, where a slicer lands the column), or down to the plate (the
//   lowest vertex along d) when the line crosses none; never negative. A line through a shared
//   edge or vertex of the faces below counts the crossing once or more, with the same height.
// How: the faces in the print frame are listed in a uniform grid of columns (uniform_grid.h) over
//   the plate; each flagged face's line visits only its own column's faces. Cost about
//   O(#F + flagged × faces per column); parallel over the flagged faces; deterministic.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

Eigen::VectorXd column_heights(const Surface& surface, const Eigen::Vector3d& d, const std::vector<bool>& faces);

}  // namespace slim
