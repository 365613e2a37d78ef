// The triangle surface the core works on, and its per-face geometry.
//
// Surface::V  #V by 3, vertex positions in the mesh's own units (MeshLab users: mm).
// Surface::F  #F by 3, vertex indices, counter-clockwise seen from outside (right-hand normals).
//
// All geometry is recomputed here in double precision from the positions: the float normals a
// mesh file or MeshLab layer carries are never trusted.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace slim {

using Points = Eigen::Matrix<double, Eigen::Dynamic, 3>;    // #P by 3
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3>;    // #F by 3

struct Surface {
  Points V;
  Triangles F;
};

// Face f's (b - a) x (c - a): its normal scaled by twice its area. Inline: loops over a million
// faces call it.
inline Eigen::Vector3d face_cross(const Points& V, const Triangles& F, Eigen::Index f) {
  const Eigen::Vector3d a = V.row(F(f, 0)).transpose();
  return (V.row(F(f, 1)).transpose() - a).cross(V.row(F(f, 2)).transpose() - a);
}
// A face cross product made unit; the zero vector when its length is 0 or not finite (a face whose
// area underflows has no direction).
inline Eigen::Vector3d unit_normal(const Eigen::Vector3d& cross) {
  const double len = cross.norm();
  return len > 0.0 && std::isfinite(len) ? Eigen::Vector3d(cross / len) : Eigen::Vector3d::Zero();
}

// #F by 3 unit normals; a zero-area face gets the zero vector (and area 0, so weight 0).
Points face_normals(const Surface& s);
Points face_normals(const Points& V, const Triangles& F);  // the same, for positions and faces held apart

// #F areas, in squared mesh units.
Eigen::VectorXd face_areas(const Surface& s);

// The length of the bounding box's diagonal of the positions V (#V by 3, mm): the part's size,
// which relative settings (the deviation budget as a share, the automatic plate tolerance) are
// shares of. 0 for no vertex.
double bbox_diagonal(const Points& V);

// Throws std::invalid_argument with a readable reason (naming the first bad vertex or face) when
// F indexes outside V or V has a non-finite coordinate. Everything downstream assumes a surface
// that passed this.
void check_surface(const Surface& s);

// The vertices that some face uses, in increasing index order (a vertex of no face is no part of
// the surface). F must index inside V (check_surface).
std::vector<Eigen::Index> face_vertices(const Surface& s);

// Signed enclosed volume (positive for a closed, outward-oriented surface). Summed about the
// vertices' centroid, so a part far from the origin loses no digits; for an open surface the
// value depends on that centre and means little.
double signed_volume(const Surface& s);

// How the faces meet along their edges. An edge is an unordered pair of vertices; a face with a
// repeated vertex has no orientation and is left out.
struct EdgeTopology {
  Eigen::Index open_edges = 0;         // used by one face only: the border of a hole or sheet
  Eigen::Index nonmanifold_edges = 0;  // used by three faces or more
  Eigen::Index flipped_edges = 0;      // used by two faces that run along it the same way
  // The first edge of each kind in (lower vertex, higher vertex) order, for messages.
  std::string first_open;         // "(3, 7)"
  std::string first_nonmanifold;  // "(3, 7) is shared by 4 faces"
  std::string first_flipped;      // "faces 2 and 9 run along edge (3, 7) in the same direction"
};
EdgeTopology edge_topology(const Surface& s);

// Throws std::invalid_argument when faces disagree along shared edges (edges.flipped_edges > 0):
// their normals then do not tell the outside of the part, which every overhang rule reads from
// them. The message names the first such edge and how to fix the mesh in MeshLab.
void require_consistent_orientation(const EdgeTopology& edges);

// Inside out: no open edge, no flipped edge, and a negative enclosed volume, so every normal
// points into the part. (Non-manifold edges are allowed: duplicated faces or solids sharing an
// edge still enclose a volume with the right sign.) The overhang rule reads the outside from the
// normals, so such a mesh is analysed with its faces turned over (see `flipped`).
bool inside_out(const Surface& s, const EdgeTopology& edges);

// The same surface with every face turned over (its second and third vertices swapped).
Surface flipped(const Surface& s);

}  // namespace slim
