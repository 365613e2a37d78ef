#include "core/optimizer/slimming_options.h"

#include <cmath>
#include <stdexcept>

namespace slim {
namespace {

bool finite_positive(double x) { return x > 0.0 && std::isfinite(x); }

void validate_coherence(const CoherenceOptions& c) {
  if (!finite_positive(c.interior_weight) || !finite_positive(c.risky_boost))
    throw std::invalid_argument("the coherent weight factors must be finite and positive");
  if (!(c.smoothing >= 0.0 && c.smoothing <= 1.0) || !(c.propagation >= 0.0 && c.propagation <= 1.0))
    throw std::invalid_argument("the coherent smoothing and propagation shares must be in [0, 1]");
  if (!(c.costly_share > 0.0 && c.costly_share <= 1.0))
    throw std::invalid_argument("the share of the support cost whose overhangs are turned must be in (0, 1]");
  if (!(c.flat_overhang_deg >= 0.0 && c.flat_overhang_deg < 90.0))
    throw std::invalid_argument("the flat-overhang angle must be in [0, 90) degrees");
  if (!(c.edge_turn_slack_deg >= 0.0 && c.edge_turn_slack_deg <= 180.0))
    throw std::invalid_argument("the edge-turn slack must be in [0, 180] degrees");
}

void validate_steps(const StepOptions& s) {
  if (s.max_k < 1) throw std::invalid_argument("the largest number of K-means proxies must be at least 1");
  if (s.margin_deg && !(*s.margin_deg >= 0.0 && *s.margin_deg < 45.0))
    throw std::invalid_argument("the angular margin must be in [0, 45) degrees");
  if (s.max_step_deg && !(*s.max_step_deg > 0.0 && *s.max_step_deg <= 180.0))
    throw std::invalid_argument("the rotation step cap must be in (0, 180] degrees");
}

void validate_choice(const ResultChoiceOptions& c, const LadderOptions& ladder) {
  if (c.max_crease_share_pct && !(*c.max_crease_share_pct > 0.0 && *c.max_crease_share_pct <= 100.0))
    throw std::invalid_argument("the crease share limit must be in (0, 100] %");
  if (c.max_mean_displacement_pct && !(*c.max_mean_displacement_pct > 0.0 && *c.max_mean_displacement_pct <= 100.0))
    throw std::invalid_argument("the mean displacement limit must be in (0, 100] % of the bbox diagonal");
  if (!(c.min_support_saving_pct >= 0.0 && c.min_support_saving_pct < 100.0))
    throw std::invalid_argument("the least support saving must be in [0, 100) % (0: any saving)");
  for (double multiple : ladder.multiples)
    if (!(multiple > 1.0 && multiple <= 4.0)) throw std::invalid_argument("the resolution ladder's multiples must be in (1, 4]");
  if (ladder.max_faces < 0) throw std::invalid_argument("the resolution ladder's face cap must be 0 or more");
}

void validate_region(const RegionOptions& r) {
  if (!(r.free_radius_share >= 0.0 && r.free_radius_share <= 10.0) || !(r.ramp_share >= 0.0 && r.ramp_share <= 10.0))
    throw std::invalid_argument("the free region's radius and ramp must be in [0, 10] times the bbox diagonal");
  if (!(r.stiffness >= 0.0 && std::isfinite(r.stiffness)))
    throw std::invalid_argument("the anchoring stiffness must be finite and 0 or more (0: the part may stretch)");
}

}  // namespace

void DeviationBudget::validate() const {
  if (kind_ == Kind::Share && !finite_positive(value_))
    throw std::invalid_argument("the deviation budget must be a finite percentage");
  if (kind_ == Kind::Length && !finite_positive(value_))
    throw std::invalid_argument("the deviation budget in mm must be finite and more than 0");
}

SlimmingOptions method_applied(const SlimmingOptions& options) {
  SlimmingOptions o = options;
  const bool paper = o.method == SlimmingMethod::Paper;
  if (!o.steps.margin_deg) o.steps.margin_deg = paper ? 1.0 : 10.0;
  if (!o.steps.max_step_deg) o.steps.max_step_deg = paper ? 10.0 : 2.0;
  if (paper) {
    o.coherence = CoherenceOptions::none();
    o.result.judge = ResultJudge::ShadowVolume;
    o.result.max_crease_share_pct.reset();
    o.result.max_mean_displacement_pct.reset();
    o.result.min_support_saving_pct = 0.0;
    o.ladder.multiples.clear();
    o.keep_volume = false;
    allow_stretch(o);
    o.guards.local_inversion_guard = false;
    o.guards.surface_guard = false;
  }
  return o;
}

void allow_stretch(SlimmingOptions& o) {
  o.region = RegionOptions::none();
  o.hold_proportions = false;
  o.guards.max_rise_pct.reset();
}

void validate_slimming_options(const SlimmingOptions& o, long faces) {
  print_rule(o.print, 1.0);  // the direction, the angle and the plate tolerance (any part size)
  if (o.steps.max_iterations < 0) throw std::invalid_argument("the iteration limit must be 0 or more");
  if (o.resolution < 1) throw std::invalid_argument("the voxel resolution must be at least 1 cell");
  validate_steps(o.steps);
  o.budget.validate();
  if (!o.rigid_features.empty() && o.rigid_features.size() != static_cast<size_t>(faces))
    throw std::invalid_argument("the rigid-feature marks must have one entry per face");
  validate_coherence(o.coherence);
  validate_region(o.region);
  validate_choice(o.result, o.ladder);
  if (o.guards.max_rise_pct && !(*o.guards.max_rise_pct >= 0.0 && *o.guards.max_rise_pct <= 100.0))
    throw std::invalid_argument("the top's allowed rise must be in [0, 100] % of the part's height");
  if (o.guards.max_memory_bytes && !(*o.guards.max_memory_bytes > 0.0))
    throw std::invalid_argument("the memory budget must be more than 0 bytes");
}

}  // namespace slim
