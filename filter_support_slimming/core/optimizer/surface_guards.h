// What the surface may not do after a global step, however the domain's tets stay valid: fold a
// face, or rise above the part's top. Every tet can stay positive while a face folds (a face's
// corners may sit in different tets), and the domain's top is not the surface's, so these guards
// look at the surface itself.
//
//   SurfaceGuards guards(input, embedding, d, max_rise_pct);
//   std::vector<int> tets = guards.faulty_tets(P);
//   roll_back_until(current, proposed, T, group, tets, [&](const Points& Q) { return guards.faulty_tets(Q); }, held);
//
// Inputs: the input surface (#V by 3 mm, #F by 3), its embedding in the domain (embedding.h), the
//   print direction d (unit) and the top's allowance: the surface's highest point may rise at most
//   max_rise_pct % of the input's height along d above the input's highest point (none: no limit).
//   Domain positions P are #DV by 3 mm.
// Output: the tets (ascending, each once) that hold a corner of a folded face, one whose normal in
//   the surface P carries (embedded_positions) points against the input's (n_input · n_P < 0, as
//   proportions.h counts them; faces of zero area in either are not judged), or a surface vertex
//   above the allowance. Rolling their vertices back (step_guards.h) mends both, since the last
//   accepted iterate had neither.
// Why the top: a part that grows taller no longer fits what it was designed for; the overhangs
//   are reshaped where they are, not by stretching the part upwards.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/domain/embedding.h"
#include "core/geometry/surface.h"

namespace slim {

// The folded faces' tets alone (used by faulty_tets and by the tests).
std::vector<int> folding_tets(const Surface& input, const Embedding& embedding, const Points& P);

class SurfaceGuards {
 public:
  SurfaceGuards(const Surface& input, const Embedding& embedding, const Eigen::Vector3d& d,
                std::optional<double> max_rise_pct);
  std::vector<int> faulty_tets(const Points& P) const;
  // The highest the surface may reach along d (mm), or none.
  std::optional<double> ceiling() const { return ceiling_; }

 private:
  const Surface& input_;
  const Embedding& embedding_;
  Eigen::Vector3d d_;
  std::optional<double> ceiling_;
};

}  // namespace slim
