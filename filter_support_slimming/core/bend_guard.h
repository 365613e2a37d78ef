// The bend guard: no edge of the surface may bend by more than a given angle from the input, so
// that slimming makes no creases (a designer's surface stays as smooth as it was drawn).
//
//   BendGuard bends(input, embedding, max_bend_deg);        // once
//   bends.faulty_tets(domain_positions)                     // every iteration, in the guards
//
// Inputs: the input surface (#V by 3 mm, #F by 3), its embedding in the domain (embedding.h), and
//   the largest change of any interior edge's dihedral angle allowed (degrees, > 0).
// Output: faulty_tets(P): for the domain at positions P (#DV by 3), the tets holding the surface
//   vertices of every interior manifold edge whose signed dihedral angle (the angle between its two
//   faces' normals; shape_metrics.h) differs from the input's by more than max_bend_deg, ascending.
//   Rolling those tets' vertices back to where they were puts every such edge back where it was.
// The metric it guards is shape_metrics.h's crease share: with max_bend_deg below its 10°
// threshold, an accepted iterate has no new crease by that measure. A bend larger than that can
// still build up over many edges (a keel rounded over a few faces), as a smooth surface may.
// Cost: O(#F) per call (the edges are listed once; the surface rebuilt through the embedding).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/embedding.h"
#include "core/shape_metrics.h"
#include "core/surface.h"

namespace slim {

class BendGuard {
 public:
  BendGuard(const Surface& input, const Embedding& embedding, double max_bend_deg);
  std::vector<int> faulty_tets(const Points& domain_positions) const;
  // The edges bent too far at these surface positions (#V by 3).
  std::vector<size_t> bent_edges(const Points& surface_positions) const;

 private:
  const Surface& input_;
  const Embedding& embedding_;
  double max_bend_deg_;
  std::vector<DihedralEdge> edges_;  // the input's, with its angles
  std::vector<std::array<int, 2>> opposite_;  // per edge: the third vertex of f0 and of f1
};

}  // namespace slim
