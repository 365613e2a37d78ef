// The orientation search's candidate directions (orientation.h, steps 1 and 3): where the search
// looks, and the pattern search that refines the best of them.
//
//   const Candidates c = candidate_directions(g, options);
//   std::vector<size_t> starts = refine_best(g, options, c, ranked, refined, scored);
//
// Inputs:  OrientationGeometry g (orientation_score.h: the faces' normals and areas, the convex
//          hull), OrientationOptions (sphere_candidates, flat_regions, hull_facets, refine_starts,
//          distinct_deg).
// Outputs: candidate_directions: unit print directions in the input's frame, the pose as given
//          (+Z) first; then sphere_candidates Fibonacci directions; for each of the largest flat
//          regions (parallel faces within 1°, at least 0.5% of the area) the direction that lays
//          it face down on the plate and the one that turns it face up; for each of the largest
//          convex-hull planes (facets within 0.05°) the direction that rests the part on it. Each
//          with its origin (words for people) and its tie rank.
//          refine_best: the refine_starts best candidates by `ranked` (indices into c, best
//          first) that lie distinct_deg apart, each refined by a pattern search on the sphere
//          (8 directions around, from the sphere's spacing down to 0.01°, by sweep_scores);
//          the refined directions go to `refined` (one per start), the sweeps made are added
//          to `scored`, and the starts' indices are returned.
// Deterministic: every step in a fixed order; the starts refine in parallel, each serially.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/orientation/orientation.h"
#include "core/orientation/orientation_score.h"

namespace slim {
namespace orientation_search {

// Among poses of equal score, which to prefer (the lower first): the pose as given (no turn at
// all), then one that rests a flat region or a hull facet exactly on the plate, then any other. A
// sphere or refined direction can tie with a resting face while tilted within the plate
// tolerance: its face would touch the plate along one edge only.
enum TieRank { kAsGiven = 0, kResting = 1, kOther = 2 };

// Every candidate direction with its origin (for people) and tie rank, the pose as given first.
struct Candidates {
  std::vector<Eigen::Vector3d> dirs;
  std::vector<std::string> origins;
  std::vector<TieRank> ranks;
  // Where the resting poses are: the flat regions face down and the hull planes, largest first.
  std::vector<size_t> flat_down, hull_rest;
  void add(const Eigen::Vector3d& d, const std::string& origin, TieRank rank) {
    dirs.push_back(d);
    origins.push_back(origin);
    ranks.push_back(rank);
  }
};

Candidates candidate_directions(const OrientationGeometry& g, const OrientationOptions& o);

std::vector<size_t> refine_best(const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                                const std::vector<size_t>& ranked, std::vector<Eigen::Vector3d>& refined, int& scored);

// The angle between two directions (radians, in [0, pi]; they need not be unit).
double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace orientation_search
}  // namespace slim
