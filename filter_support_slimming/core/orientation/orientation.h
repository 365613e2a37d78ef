// Print orientation: the build direction that needs the least support.
//
// In:  a Surface (#V by 3 positions in mm, #F by 3 outward-oriented faces) in any pose, and
//      OrientationOptions (the overhang rule of overhang.h, the search effort).
// Out: OrientationResult: the best print direction d (a unit vector in the input's frame), the
//      rotation R that takes the input frame to the print frame (R d = +Z), the best candidates
//      with their scores, and the score of the pose as given (d = +Z).
//      apply_orientation(surface, R) gives the mesh in its print pose: +Z up, resting on z = 0.
//
// The score of a direction d (mm³, lower is better) is
//
//   score(d) = shadow_volume(d) - contact_bonus_height * contact_area(d)
//
//   shadow_volume(d) = sum over risky faces f of  area_f * (-n_f·d) * (c_f·d - plate(d))
//
// with exactly the overhang rule of analyse_overhang() for print direction d (so shadow_volume(d)
// equals OverhangReport::shadow_volume): f is risky when n_f·d + sin(alpha_max) < 0 and it does
// not rest on the plate; plate(d) = min over vertices of v·d; a face rests on the plate when its
// three vertices lie within plate_tolerance of it; c_f is its centroid. It is the volume of the
// prisms between each overhang and the plate: a slicer's support columns, ignoring that they
// stand on the part itself in places. (It ranks poses by PrusaSlicer's support far better than the
// plain risky area does: docs/orientation.md.)
//
//   contact_area(d) = the area of the faces resting on the plate
//
// A large flat contact holds the part on the plate and costs no support at all; the bonus also
// decides between poses that need no support (a bracket flat on its largest face rather than on
// its edge). contact_bonus_height = contact_bonus * part size, part size = the diameter of the
// vertices about their centroid (2 max |v - centroid|), so the score does not depend on the pose
// the part came in. The bonus is small: it trades at most that thin a slab of support per mm² of
// contact.
//
// The search (deterministic; every step in a fixed order; among equal scores the pose as given
// wins, then a pose that lays a flat region or a hull facet exactly on the plate, then the
// direction nearer +Z, then the earlier candidate; the same with any thread count), the score a
// fast prefilter and the support model the judge:
//   1. candidates: the pose as given (+Z); sphere_candidates directions on a Fibonacci sphere;
//      for the largest flat regions of the surface (parallel faces, by area) the directions that
//      put them face down on the plate or face up; for the largest convex-hull facets, the pose
//      that rests the part on them.
//   2. all are scored (vectorised over faces, in blocks of directions, in parallel over blocks);
//   3. a pattern search on the sphere refines the refine_starts best distinct ones (halving its
//      step from the candidate spacing down to 0.01°);
//   4. the best pool is scored once more, exactly (the plate from every vertex, the plate rule
//      face by face), and the top distinct ones (>= distinct_deg apart) kept;
//   5. the support model judges the poses (pose_judging.h): the pose as given, the best by score,
//      and the poses a user would try (the largest convex-hull facets and flat regions resting on
//      the plate, the principal axes both ways, the largest clusters of face normals face down,
//      directions spread over the sphere), support_model_candidates in all, each at one grid
//      phase and a coarser raster; the best support_model_finalists of them and the pose as given
//      in full. The least support wins, with two exceptions: within
//      5% + 1 mm³ of the least, a pose that stands on the plate by itself (its centre of mass over
//      its footprint, pose_stability.h) beats one balanced on a point or an edge; within 1% +
//      1 mm³ (the model's noise), the pose resting the most area on the plate wins, then the pose
//      as given, then the better coarse estimate. The score only gathers the candidates: it
//      decides nothing here.
//
// Errors: std::invalid_argument with a readable reason for a mesh with no faces, bad indices,
// non-finite coordinates, zero extent or zero area, faces that are not consistently oriented
// (their normals do not tell the outside), or options out of range. A closed mesh that is inside
// out is searched turned over (OrientationResult::inside_out).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/checked_surface.h"
#include "core/geometry/surface.h"
#include "core/print/overhang.h"
#include "core/print/rotation_to_up.h"

namespace slim {

enum class OrientationEffort { Fast, Normal, Thorough };

struct OrientationOptions {
  double alpha_max_deg = 45.0;      // self-supporting angle from the vertical, [0, 90)
  // Which faces rest on the plate; automatic: 1e-3 of the bbox diagonal of the part as given, one
  // length for every pose.
  PlateRule plate = PlateRule::automatic();
  double contact_bonus = 0.01;      // bonus height as a share of the part size, >= 0
  int sphere_candidates = 4000;     // Fibonacci directions, >= 1
  int flat_regions = 32;            // largest flat regions tried face down and face up, >= 0
  int hull_facets = 256;            // largest convex-hull facets tried as resting faces, >= 0
  int refine_starts = 8;            // best distinct candidates refined locally, >= 0
  int report_count = 10;            // candidates returned in OrientationResult::top, >= 1
  // The final choice (step 5): the support model (support_model.h, what the slicer builds) judges
  // this many distinct poses at one grid phase (0: the score alone decides), then the best
  // finalists of them, and the pose as given, in full.
  int support_model_candidates = 64;
  int support_model_finalists = 8;
  double distinct_deg = 5.0;        // candidates closer than this count as one pose, [0, 180]
  int threads = 0;                  // OpenMP threads; 0: the runtime's default. Results do not
                                    // depend on it.
};

// The options for a search effort: Fast (1000 sphere directions, 4 refined, 32 poses judged by
// the model, 4 in full), Normal (the defaults: 4000, 8, 64, 8) or Thorough (16000, 16, 128, 16),
// everything else as in `base`.
OrientationOptions with_effort(OrientationEffort effort, OrientationOptions base = {});

struct OrientationCandidate {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // print direction, input frame, unit
  double score = 0.0;          // mm³: shadow_volume - contact_bonus_height * contact_area
  double shadow_volume = 0.0;  // mm³
  double contact_area = 0.0;   // mm², faces resting on the plate
  double risky_area = 0.0;     // mm², risky faces (as in OverhangReport::risky_area)
  std::optional<double> support_estimate;  // mm³, the support model's estimate; none: not judged by it
  double footprint_area = 0.0; // mm², convex hull of the vertices on the plate (judged poses only)
  bool stable = false;         // its centre of mass lies over that footprint (judged poses only)
  std::string origin;          // "as given", "sphere", "flat face down", "flat face up", "hull facet",
                               // "principal axis", "face cluster down", or one of the first five
                               // followed by " refined"
};

struct OrientationResult {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // input frame -> print frame
  OrientationCandidate best;
  OrientationCandidate as_given;          // the input's own pose, d = +Z
  // The chosen pose first, then the others the model judged in full, least support first (by the
  // score when the model judged none); pairwise >= distinct_deg apart, at most report_count.
  std::vector<OrientationCandidate> top;
  double contact_bonus_height = 0.0;      // mm, as used in the score
  std::optional<double> plate_tolerance_mm;  // mm, as used; none: no plate rule
  int candidates = 0;                     // directions scored, refinement included
  int judged_coarse = 0, judged_fine = 0; // poses the support model judged at one phase, in full
  int hull_facets = 0;                    // facets of the convex hull (0: it could not be built)
  bool inside_out = false;                // searched with the faces turned over
  double seconds = 0.0;                   // wall time of the search
};

OrientationResult optimize_orientation(const Surface& surface, const OrientationOptions& options = {});
// The same for a surface already checked.
OrientationResult optimize_orientation(const CheckedSurface& surface, const OrientationOptions& options = {});

// The score of one print direction (any non-zero vector), computed as the search's final step
// does. Same errors as optimize_orientation.
OrientationCandidate score_orientation(const Surface& surface, const Eigen::Vector3d& direction,
                                       const OrientationOptions& options = {});

// count unit vectors spread evenly over the sphere (a Fibonacci spiral from near +Z to near -Z):
// the search's sphere candidates.
std::vector<Eigen::Vector3d> fibonacci_sphere(int count);

// The rigid motion into the print pose: x -> R (x - c) + c, then along Z so that the lowest
// vertex lies on z = 0 (c: the vertices' centroid, so the part turns in place).
Eigen::Matrix<double, 3, 4> print_placement(const Surface& surface, const Eigen::Matrix3d& rotation);

// The surface in its print pose (print_placement applied to every vertex; faces unchanged).
Surface apply_orientation(const Surface& surface, const Eigen::Matrix3d& rotation);

// The plate rule the search used, as a rule to hand on: the slimming in the chosen pose then sees
// the plate as the search did.
inline PlateRule plate_rule_as_used(const OrientationResult& result) {
  return result.plate_tolerance_mm ? PlateRule::within(*result.plate_tolerance_mm) : PlateRule::none();
}

// The overhangs of `posed` (apply_orientation(input, result.rotation)) for print direction +Z,
// with the search's plate tolerance, turned over when the input was inside out: what the result
// layer shows.
OverhangReport print_pose_overhang(const Surface& posed, const OrientationResult& result, double alpha_max_deg);

}  // namespace slim
