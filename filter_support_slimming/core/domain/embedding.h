// The embedding of the surface M in the tet domain T (paper §II): after each global step the
// surface follows the domain through fixed barycentric coordinates, and the local step of tet t
// looks at the surface faces that lie in t.
//
// embed_surface(surface, domain, options) -> Embedding
//   surface  Surface{V #V by 3, F #F by 3}, mesh units (mm).
//   domain   a VoxelDomain (cells give the candidate tets directly) or any TetMesh (a uniform
//            grid of tet boxes finds them; used for the TetGen domain): tet_locator.h. It must enclose every
//            surface vertex; otherwise std::invalid_argument names the first vertex outside.
//
// Embedding
//   vertex_tet    #V      the tet that holds each surface vertex.
//   vertex_nodes  #V by 4 that tet's domain vertices (domain.T.row(vertex_tet(i))).
//   vertex_bary   #V by 4 barycentric coordinates in that tet: they sum to 1 (to rounding), each
//                 is >= -outside_tolerance, and sum_k bary(i,k) * domain.V.row(nodes(i,k))
//                 rebuilds vertex i to rounding. On a face, edge or vertex shared by several
//                 tets the vertex goes to the tet whose smallest coordinate is largest (the first
//                 such tet in candidate order on exact ties), so the choice is deterministic.
//   The faces each tet contains, CSR-like (#T + 1 offsets into #P "pieces"):
//   tet_face_offsets  #T + 1; the pieces of tet t are offsets(t) .. offsets(t+1) - 1
//   tet_faces         #P surface face ids, ascending within a tet
//   tet_face_areas    #P area of that face inside that tet (mm²)
//   A face crossing several tets is clipped against each of them (Sutherland–Hodgman against the
//   tet's four planes), so each tet gets its share of the area and the shares of a face sum to
//   its area. This matters for coarse CAD triangles that span many tets: by centroid only one of
//   them would see the face. A face lying in a plane shared by two tets goes to one of them: the
//   one on the face's back side (inside the solid for an outward-oriented mesh). Pieces below
//   1e-12 of the face's area (a tet touching the face along an edge: rounding noise) are
//   dropped and their area given to the face's largest piece, and so is area that clipping loses
//   to rounding (a needle face: up to about 64 eps x its longest edge x the size of the
//   coordinates, beyond the 1e-6 share allowed anyway; more counts as outside the domain). A
//   zero-area face is one piece of area 0 in its first vertex's tet. The topology never changes.
//
// embedded_positions(embedding, domain_V, surface_V) rebuilds the surface from deformed domain
// vertices (#DV by 3 -> #V by 3): one 4-term sum per vertex, meant to run every iteration.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/domain/voxel_domain.h"
#include "core/geometry/checked_surface.h"
#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"

namespace slim {

enum class FaceAssignment {
  clip,      // exact area split by clipping (default)
  centroid,  // each whole face to the tet holding its centroid: only for measuring what clipping buys
};

struct EmbeddingOptions {
  FaceAssignment faces = FaceAssignment::clip;
  // How far outside its tet a vertex may lie, in barycentric units, before it counts as outside
  // the domain (the voxel grid's outer layer is clamped, so rounding can push it out by ~1e-15).
  double outside_tolerance = 1e-9;
};

struct Embedding {
  Eigen::VectorXi vertex_tet;
  Eigen::Matrix<int, Eigen::Dynamic, 4> vertex_nodes;
  Eigen::Matrix<double, Eigen::Dynamic, 4> vertex_bary;
  Eigen::VectorXi tet_face_offsets;
  Eigen::VectorXi tet_faces;
  Eigen::VectorXd tet_face_areas;
  Eigen::Index split_faces = 0;  // faces that lie in more than one tet (for the log)
};

// Throws std::invalid_argument (check_surface, or a vertex or face outside the domain).
Embedding embed_surface(const Surface& surface, const VoxelDomain& domain, const EmbeddingOptions& options = {});
Embedding embed_surface(const Surface& surface, const TetMesh& domain, const EmbeddingOptions& options = {});
// The same for a surface already checked.
Embedding embed_surface(const CheckedSurface& surface, const VoxelDomain& domain, const EmbeddingOptions& options = {});
Embedding embed_surface(const CheckedSurface& surface, const TetMesh& domain, const EmbeddingOptions& options = {});

// surface_V = sum of bary * domain_V, #V by 3; resized as needed.
void embedded_positions(const Embedding& embedding, const Points& domain_V, Points& surface_V);

}  // namespace slim
