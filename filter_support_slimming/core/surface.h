// The triangle surface the core works on, and its per-face geometry.
//
// Surface::V  #V by 3, vertex positions in the mesh's own units (MeshLab users: mm).
// Surface::F  #F by 3, vertex indices, counter-clockwise seen from outside (right-hand normals).
//
// All geometry is recomputed here in double precision from the positions: the float normals a
// mesh file or MeshLab layer carries are never trusted.
#pragma once

#include <Eigen/Core>

namespace slim {

using Points = Eigen::Matrix<double, Eigen::Dynamic, 3>;    // #P by 3
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3>;    // #F by 3

struct Surface {
  Points V;
  Triangles F;
};

// #F by 3 unit normals; a zero-area face gets the zero vector (and area 0, so weight 0).
Points face_normals(const Surface& s);

// #F areas, in squared mesh units.
Eigen::VectorXd face_areas(const Surface& s);

// Throws std::invalid_argument with a readable reason when F indexes outside V or V has a
// non-finite coordinate. Everything downstream assumes a surface that passed this.
void check_surface(const Surface& s);

// Signed enclosed volume (positive for a closed, outward-oriented surface).
double signed_volume(const Surface& s);

}  // namespace slim
