// The boundary of a flat overhang region, and which way its faces should turn.
//
// A face pointing straight down against the print direction d can be made self-supporting by
// turning it about any horizontal axis: every way is equally short (min_rotation.h, tie_break),
// and for a face a few degrees off it the other ways cost only a little more. Within a small
// deviation budget only a strip along the region's boundary can reach the self-supporting slope,
// as a bevel or a keel along that edge; the middle of a wide flat overhang cannot. So each face
// of the region should turn towards its nearest boundary edge: the strips along opposite edges
// then meet in a ridge, instead of the whole region tilting one way about a far-away pivot
// (which needs far more displacement than the budget allows).
//
// In:  a Surface (positions in mm, #F by 3 triangles) and one flag per face marking the region
//      (slimming.cpp marks the risky faces within a few degrees of straight down).
// Out: the boundary segments: every edge of a marked face that no other marked face shares (an
//      edge to an unmarked face, or an open edge), as pairs of end points in mm. Queries return,
//      for a point, the unit direction perpendicular to d from it to the nearest boundary point.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"
#include "core/geometry/uniform_grid.h"

namespace slim {

class OverhangBoundary {
 public:
  // Throws std::invalid_argument when region does not have one flag per face.
  OverhangBoundary(const Surface& s, const std::vector<bool>& region);

  Eigen::Index segment_count() const { return a_.rows(); }
  // Segment i's end points (mm), for 0 <= i < segment_count(); in edge order (lower vertex index
  // first), so the listing never depends on the face order.
  Eigen::Vector3d segment_start(Eigen::Index i) const { return a_.row(i).transpose(); }
  Eigen::Vector3d segment_end(Eigen::Index i) const { return b_.row(i).transpose(); }

  // The unit vector perpendicular to the unit vector d from p towards the nearest boundary point
  // (Euclidean distance in 3D; ties go to the segment listed first). Zero when there is no
  // boundary, or when the nearest point lies straight above or below p (within 1e-12 of the
  // distance).
  Eigen::Vector3d toward_nearest(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const;

  // The nearest boundary point to p, and its distance (mm); HUGE_VAL with no boundary.
  double nearest(const Eigen::Vector3d& p, Eigen::Vector3d& closest) const;

 private:
  Points a_, b_;  // segment end points, one row each
  // Each cell lists the segments whose bounding box overlaps it, so a query visits shells of
  // cells outwards from its own.
  UniformGrid grid_;
};

}  // namespace slim
