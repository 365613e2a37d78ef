// How a tet domain finds the tets near a point or a triangle, for the embedding (embedding.h).
//
// A TetLocator works in its own coordinates W: grid cell units for the voxel domain (exact
// integers on the grid planes, so a face on a plane is seen the same way from both sides), world
// units about the domain's centre for any other tet mesh (so a part far from the origin loses no
// digits).
//
//   voxel_locator(surface, domain)  VoxelDomain: a point's cell is its floor; a tet's cell and Kuhn
//                                   index follow from its number (6 per kept cell).
//   mesh_locator(surface, domain)   any TetMesh (the TetGen domain): a uniform grid of tet
//                                   bounding boxes, about one cell per tet.
// Inputs:  the surface (#V by 3, mm) whose vertices are mapped into W, and the domain.
// Outputs: TetLocator
//   W           #V by 3 surface vertices in working coordinates
//   area_scale  mm² per working area unit
//   plane_eps   points this close to a tet plane are "on" it (working units)
//   point_candidates(w)       tets that may contain w: a superset, in ascending order
//   triangle_candidates(a,b,c) tets that may meet the triangle: a superset, each once, ascending
//   barycentric(t, w)         w's barycentric coordinates in tet t (TetMesh::T order)
//   planes(t)                 t's four inward planes; a face shared by two tets yields exactly
//                             negated values, so clipping against neighbours is consistent
// The locator borrows the domain: it must outlive the locator. mesh_locator throws
// std::invalid_argument for an empty domain, a non-finite vertex or an index out of range.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/domain/kuhn_split.h"
#include "core/domain/voxel_domain.h"
#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"

namespace slim {

class TetLocator {
 public:
  virtual ~TetLocator() = default;
  virtual void point_candidates(const Eigen::Vector3d& w, std::vector<int>& out) const = 0;
  virtual void triangle_candidates(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                   std::vector<int>& out) const = 0;
  virtual Eigen::Vector4d barycentric(int t, const Eigen::Vector3d& w) const = 0;
  virtual TetPlanes planes(int t) const = 0;

  Points W;
  double area_scale = 1.0;
  double plane_eps = 0.0;
};

std::unique_ptr<TetLocator> voxel_locator(const Surface& surface, const VoxelDomain& domain);
std::unique_ptr<TetLocator> mesh_locator(const Surface& surface, const TetMesh& domain);

}  // namespace slim
