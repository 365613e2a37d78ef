// What a voxel domain (voxel_domain.h) of a given resolution would cost, and the guard that
// refuses one that does not fit: computed from the surface's extent alone, before anything
// proportional to the grid is allocated.
//
// Inputs: a surface (#V by 3, mm), a print direction d (any non-zero vector), a resolution (cells
//         along the longest side of the bounding box in the grid frame), a budget in bytes.
// Outputs
//   frame_box(s, axes)            the surface's bounding box in the frame with rows `axes`, mm
//   voxel_cells(extent, r)        cells per axis for frame extent `extent` (mm) at resolution r,
//                                 in double so that an absurd request cannot overflow
//   estimate_voxel_domain(s, d, r)  the grid and its worst case (every cell kept): cells, tets, bytes
//   max_voxel_resolution(s, d, b)   the largest resolution (>= 1) whose worst case fits in b bytes;
//                                   0 when not even 1 fits
//   require_voxel_budget(extent, r, b)  throws DomainTooLarge (an std::invalid_argument saying how
//                                 big the request was and which resolution fits) when it does not
// The worst case counts about 140 bytes per cell (the domain's flags, votes, ranks and 6 tets, the
// embedding's per-tet offsets) and 29 per grid node; tets and nodes must also fit 32-bit indices.
#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

struct FrameBox {
  Eigen::Vector3d lo, hi;  // frame coordinates (mm)
};
FrameBox frame_box(const Surface& s, const Eigen::Matrix3d& axes);

Eigen::Vector3d voxel_cells(const Eigen::Vector3d& extent, int resolution);

struct VoxelDomainSize {
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();  // along e1, e2, d (saturates at INT_MAX)
  double cell_count = 0;                            // all cells of the grid
  double max_tets = 0;                              // 6 per cell: every cell kept
  double max_bytes = 0;                             // worst-case memory of building the domain
};
// Both throw std::invalid_argument for a surface with no faces, bad indices or coordinates, zero
// extent, a zero print direction or a resolution below 1.
VoxelDomainSize estimate_voxel_domain(const Surface& surface, const Eigen::Vector3d& d, int resolution);
int max_voxel_resolution(const Surface& surface, const Eigen::Vector3d& d, double max_bytes);

class DomainTooLarge : public std::invalid_argument {
 public:
  DomainTooLarge(const std::string& what, double cells, double tets, double bytes, int fitting_resolution)
      : std::invalid_argument(what), cells(cells), tets(tets), bytes(bytes), fitting_resolution(fitting_resolution) {}
  double cells, tets, bytes;  // what the request would need (worst case)
  int fitting_resolution;     // the largest resolution within the budget
};
void require_voxel_budget(const Eigen::Vector3d& extent, int resolution, double max_bytes);

// The frame extent of a checked surface (frame_box's hi - lo); throws std::invalid_argument for no
// faces or zero extent.
Eigen::Vector3d voxel_extent(const Surface& checked, const Eigen::Matrix3d& axes, FrameBox& box);

}  // namespace slim
