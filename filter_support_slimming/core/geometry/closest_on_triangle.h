// The closest point of a triangle to a point, exactly: the kernel of every distance to a surface
// (face_box_tree.h, surface_distance.h).
//
//   Eigen::Vector3d x = closest_on_triangle(q, p0, p1, p2);
//
// In: the point q and the triangle's corners p0, p1, p2 (mm). Out: the point of the triangle
// nearest to q (mm). By the Voronoi regions of the corners, the edges and the face (Ericson,
// Real-Time Collision Detection); a triangle without area (collinear or coincident corners) is
// taken as the nearest of its three edges.
#pragma once

#include <Eigen/Core>

namespace slim {

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& q, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                    const Eigen::Vector3d& p2);

}  // namespace slim
