// The orientation search's final choice (orientation.h, step 5): the poses a user would try and
// the score's best, judged by the support model, coarsely first and then in full.
//
//   judge_poses(surface, g, options, candidates, ranked, result);
//
// Inputs:  the surface the search ran on (#V by 3 mm, #F by 3; turned over when it was inside
//          out), its OrientationGeometry g, the options, the candidates (orientation_candidates.h)
//          with their sweep order `ranked` (indices into them, best score first), and `result`
//          holding the exact pool's choice by score (result.best, result.top, result.as_given).
// Outputs: result.best, result.rotation and result.top replaced by the model's choice:
//          - the pool: the pose as given, then one pose from each source in turn: the score's
//            best (result.top), the largest convex-hull facets and flat regions resting on the
//            plate, the principal axes of the surface both ways, the largest clusters of face
//            normals face down (an axis or a cluster within distinct_deg of a resting pose is
//            moved onto it), the next best by score, 48 directions spread over the sphere; pairwise >= distinct_deg apart (the
//            earlier wins), support_model_candidates of them, fewer on a large mesh;
//          - the coarse pass: each estimated by the model at one grid phase and half the raster
//            resolution (a small share of the full estimate's work), on the threads at once;
//          - the fine pass: the best support_model_finalists by the coarse estimate, and the pose
//            as given, estimated in full (support_estimate), with their rest on the plate
//            (pose_stability.h: footprint, stable);
//          - the choice (below); result.top is then the finalists by the model's estimate, the
//            chosen pose first, at most report_count of them.
//          result.judged_coarse and judged_fine count the estimates made.
// The choice: among the finalists within 5% + 1 mm³ of the least support, the poses that stand on
// the plate by themselves if there are any; among those, the least support, and within 1% + 1 mm³
// of it (the model's noise between phases), the one resting the most area on the plate, then the
// pose as given, then the better coarse estimate. Nothing measurable (the model refuses every
// pose): the score's choice stands.
#pragma once

#include <optional>
#include <vector>

#include "core/geometry/surface.h"
#include "core/orientation/orientation.h"
#include "core/orientation/orientation_candidates.h"
#include "core/orientation/orientation_score.h"

namespace slim {
namespace orientation_search {

void judge_poses(const Surface& surface, const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                 const std::vector<size_t>& ranked, OrientationResult& result);

// The choice among poses the model judged in full (the rule above): the index of the chosen one;
// judged[0] is the pose as given. None when no pose has an estimate.
std::optional<size_t> model_choice(const std::vector<OrientationCandidate>& judged);

// The principal axes of the surface's area (unit, in the input's frame; the eigenvectors of the
// second moment of the faces' area about its centroid), largest spread first.
std::vector<Eigen::Vector3d> principal_axes(const OrientationGeometry& g);

}  // namespace orientation_search
}  // namespace slim
