// The Support Slimming optimizer as a stateful solver: the precomputation once, then one
// local/global iteration per step() (libigl's *_precomputation / *_solve split; slimming.h's
// slim_supports is the driver around it).
//
//   SupportSlimmer slimmer(input, std::move(domain), before, options, rule, report);
//   IterationStats stats = slimmer.step();       // as often as the stopping rule allows
//   slimmer.surface_positions(), slimmer.overhang(), slimmer.displacement()
//
// Inputs
//   input    the checked surface, outward-oriented (slim_supports turns an inside-out one over);
//            #V by 3 mm, #F by 3. It must outlive the slimmer.
//   domain   its EmbeddedDomain (embedded_domain.h), moved in.
//   before   the input's overhangs at alpha_max with the run's plate tolerance (overhang.h).
//   options  SlimmingOptions, validated and with the method applied (method_applied()).
//   rule     the input's SlimmingRule: its diagonal, print rule and deviation budget.
//   report   progress, called once before the factorization (fraction 0.05); it may throw.
// The constructor (the precomputation): the memory guard (refuses, before anything big is
// allocated, a domain whose optimizer would need more than options.guards.max_memory_bytes, naming a
// resolution that fits); the local step's rest inverses and constraint pieces (local_step.h);
// the tie directions and edge turns (coherence.h); the rigid features (rigid_features.h); the
// global step's weights and its one factorization (arap.h), with the domain's plate vertices
// held; the tets' neighbours for the blend.
// step(): local step, blend, feature fits, global step, then the guards (step_guards.h): the
//   plate, the deviation budget, the inversion guard; the surface follows through the embedding.
//   Returns the iterate's statistics (slimming.h: IterationStats); the iterate becomes current.
// Outputs of the current iterate: surface_positions() #V by 3 mm, overhang() at alpha_max,
//   displacement() #V from the input (mm); guard_stop(): why a guard ended the run in this step
//   (the paper's inversion guard cut the whole step back), empty when none did.
// Errors: std::invalid_argument from the memory guard; std::runtime_error from the global step.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/domain/embedded_domain.h"
#include "core/geometry/checked_surface.h"
#include "core/optimizer/local_step.h"
#include "core/optimizer/rigid_features.h"
#include "core/optimizer/slimming_options.h"
#include "core/optimizer/slimming_result.h"
#include "core/optimizer/surface_guards.h"
#include "core/optimizer/volume_keeping.h"
#include "core/print/overhang.h"
#include "core/solver/arap.h"

namespace slim {

// What a run derives from its input and options, once for every rung: the input's bounding-box
// diagonal (mm, > 0), the print rule resolved for it, and the deviation budget in mm (none: no
// budget). Throws std::invalid_argument for a bad print setup (slim_supports refused a part with no
// extent before: check_slimming_input, slimming.h).
struct SlimmingRule {
  double diagonal_mm = 0.0;
  PrintRule print;
  std::optional<double> budget_mm;
};
SlimmingRule slimming_rule(const Surface& input, const SlimmingOptions& options);

class SupportSlimmer {
 public:
  SupportSlimmer(const CheckedSurface& input, EmbeddedDomain domain, const OverhangReport& before,
                 const SlimmingOptions& options, const SlimmingRule& rule,
                 const std::function<void(double, const std::string&)>& report);

  IterationStats step();

  // Its parts hold references to its own members (the volume keeping reads the domain's embedding).
  SupportSlimmer(const SupportSlimmer&) = delete;
  SupportSlimmer& operator=(const SupportSlimmer&) = delete;

  const Points& surface_positions() const { return current_.V; }
  const OverhangReport& overhang() const { return overhang_; }
  const Eigen::VectorXd& displacement() const { return displacement_; }
  const std::string& guard_stop() const { return guard_stop_; }
  const SlimmingStageSeconds& stage_seconds() const { return times_; }
  std::string backend_name() const { return arap_->backend_name(); }

 private:
  void factor_global_step(const std::vector<bool>& costly, double diagonal_mm);
  // The guards on the global step's solution; true when they moved it.
  bool guard(Points& proposed, int& held_back, int& features_held, bool& inversion_cut);
  IterationStats measure(const Points& solved, const Points& accepted, bool guarded, bool inversion_cut, int held_back);

  const Surface& input_;
  SlimmingOptions options_;
  EmbeddedDomain domain_;
  PrintRule measure_;
  std::optional<double> budget_;
  double plate_ = 0.0, piece_area_ = 0.0, volume_target_ = 0.0;
  LocalStep local_;
  LocalStepState state_;
  std::unique_ptr<RigidFeatures> features_;
  Eigen::VectorXd weights_;
  std::unique_ptr<ArapSolver> arap_;
  std::unique_ptr<VolumeKeeping> volume_;  // when the coherent options keep the volume
  std::unique_ptr<SurfaceGuards> surface_guards_;  // none for the paper's method
  std::vector<std::vector<int>> neighbours_;
  Points V_;             // the current domain positions
  Surface current_;      // the current surface: its positions, the input's faces
  CheckedSurface current_view_;
  OverhangReport overhang_;
  Eigen::VectorXd displacement_;
  std::string guard_stop_;
  SlimmingStageSeconds times_;
};

// Peak memory of the optimizer for a domain of `tets` tets and `vertices` vertices, in bytes:
// about 650 bytes per tet (rest inverses, L, M and the extra rotations, face pieces, ARAP's rest
// shapes and incidence) plus the Cholesky factor, whose fill on a 3D grid grows like #DV^(4/3)
// (about 90 bytes each); measured as the peak RSS of one iteration on solid cubes of 260k to 2M
// tets (CHOLMOD), rounded up so that the guard errs on the side of refusing.
double optimizer_bytes(Eigen::Index tets, Eigen::Index vertices);

}  // namespace slim
