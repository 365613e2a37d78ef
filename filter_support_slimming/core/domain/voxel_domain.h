// The voxel tet domain: the volumetric mesh T that encloses the surface M (paper §II).
//
// voxel_domain(surface, d, options) lays a regular grid of cubes over the surface, aligned with
// the print direction d, keeps every cell that the surface passes through or that lies inside it,
// and splits each kept cell into 6 tets.
//
// Inputs
//   surface  Surface{V #V by 3, F #F by 3}, mesh units (mm). It need not be closed or manifold.
//   d        print direction, any non-zero vector (normalised here).
//   options  VoxelDomainOptions below.
// Output: VoxelDomain
//   mesh.V       #DV by 3 grid nodes used by kept cells, world coordinates (mesh units), in the
//                order of their grid index (k, then j, then i).
//   mesh.T       #DT by 4, 6 tets per kept cell, kept cells in the order of their grid index.
//                Every tet has positive volume (tet_mesh.h).
//   grid         the frame, the cell size and the number of cells (VoxelGrid below).
//   plate_height min over surface vertices of d·v (mm): the build plate.
//   on_plate     #DV, true for the nodes of grid layer 0, which lies exactly on the plate.
//
// The grid frame. e1, e2, d is right-handed and orthonormal, chosen from d alone (print_frame in
// voxel_grid.h), so the same d always gives the same grid. Grid plane 0 along d is the plate: the lowest vertex has
// grid height 0, so the global step can pin the nodes on it and nothing sits below it.
//
// Which cells are kept.
//   * Surface cells: every cell whose closed box, grown by `surface_tolerance` cell units, overlaps
//     a face (exact slab clipping, cells_overlapping_triangle). A face lying on a grid plane thus
//     marks the cells on both sides, and every vertex's cell is kept, so the domain encloses the
//     whole surface, open, non-manifold or not.
//   * Inside cells: signed crossing counts along grid lines through cell centres, in the six
//     directions ±e1, ±e2, ±d. A ray votes "inside" when the faces it crosses do not cancel (the
//     winding number along that ray is non-zero), and a cell needs `min_inside_votes` of the six.
//     Closed meshes give six equal votes; a hole in the mesh only spoils the rays that pass through
//     it, so a shell with a hole in its base is still filled. Signed counts (not parity) keep
//     overlapping shells filled. One pass over the faces per axis: no per-cell winding number,
//     which would be far too slow for a 1M-face mesh. An open bowl is ambiguous: its
//     surface cells are always kept, its air is kept only when enough rays see it as enclosed.
//
// The split. Every cell is split into the 6 Kuhn tets around its main diagonal (kuhn_split.h).
// The split is the same in every cell, so neighbouring cells share their face triangles and the
// tet mesh is conforming.
//
// The memory guard (voxel_budget.h). The grid size is known before anything is allocated; when the
// worst case (every cell kept) exceeds options.max_bytes, voxel_domain throws DomainTooLarge (an
// std::invalid_argument) saying how big the request was and which resolution fits.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/domain/kuhn_split.h"
#include "core/domain/triangle_cells.h"
#include "core/domain/voxel_budget.h"
#include "core/domain/voxel_grid.h"
#include "core/geometry/checked_surface.h"
#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"

namespace slim {

struct VoxelDomainOptions {
  // Cells along the longest side of the bounding box, measured in the grid frame. 24 is the
  // coarsest rung of the slimming's resolution ladder (slimming_options.h): a compact part gets a
  // few thousand cells, cheap to factor.
  int resolution = 24;
  // Budget for the domain and its embedding in bytes, worst case (all cells kept, about 140 bytes
  // per cell): 2 GB, about 14M cells, a resolution of about 240 for a cube. Above: DomainTooLarge.
  double max_bytes = 2e9;
  // Growth of each cell's box, in cell units, in the surface test, so rounding never drops the
  // cell on either side of a face that lies on a grid plane.
  double surface_tolerance = 1e-9;
  // A cell centre is inside when at least this many of the 6 axis rays say so (1..6). 4 is a
  // majority: a closed mesh gives 6, a cell above a hole in the base typically 5.
  int min_inside_votes = 4;
};

struct VoxelDomain {
  TetMesh mesh;
  VoxelGrid grid;
  double plate_height = 0.0;
  Eigen::Array<bool, Eigen::Dynamic, 1> on_plate;  // #DV
  // #DT / 6: grid index of each kept cell, ascending; tets 6c .. 6c+5 belong to kept cell c, tet
  // 6c + p being Kuhn tet p.
  std::vector<std::int64_t> kept_cells;
  // grid.cell_count(): the rank of the cell in kept_cells, or -1 when the cell was dropped.
  std::vector<int> cell_rank;
  std::int64_t surface_cells = 0;  // kept because a face passes through them
  std::int64_t inside_cells = 0;   // kept only because they are inside
};

// Builds the domain. Throws std::invalid_argument for an empty surface, zero extent, bad
// indices or non-finite coordinates (check_surface), a zero print direction or bad options, and
// DomainTooLarge above the budget (voxel_budget.h).
VoxelDomain voxel_domain(const Surface& surface, const Eigen::Vector3d& d, const VoxelDomainOptions& options = {});
// The same for a surface already checked.
VoxelDomain voxel_domain(const CheckedSurface& surface, const Eigen::Vector3d& d, const VoxelDomainOptions& options = {});

}  // namespace slim

