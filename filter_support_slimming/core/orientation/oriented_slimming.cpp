#include "core/orientation/oriented_slimming.h"

namespace slim {

OrientedSlimming slim_in_best_pose(const Surface& surface, SlimmingOptions slimming, OrientationOptions orientation) {
  orientation.alpha_max_deg = slimming.print.alpha_max_deg;
  orientation.plate = slimming.print.plate;
  orientation.threads = slimming.threads;
  OrientedSlimming job;
  job.orientation = optimize_orientation(surface, orientation);
  job.posed = apply_orientation(surface, job.orientation.rotation);
  slimming.print.direction = Eigen::Vector3d::UnitZ();
  slimming.print.plate = plate_rule_as_used(job.orientation);
  // The budget is the user's: a share of the part as they gave it, a length that the turn does not
  // change (the posed part's bounding box is another one).
  if (slimming.budget.is_share()) slimming.budget = DeviationBudget::length(*slimming.budget.mm(bbox_diagonal(surface.V)));
  job.slimming = slim_supports(job.posed, slimming);
  return job;
}

OrientedSlimming slim_as_asked(const Surface& surface, const SlimmingOptions& slimming,
                               const std::optional<OrientationOptions>& orientation) {
  if (orientation) return slim_in_best_pose(surface, slimming, *orientation);
  OrientedSlimming job;
  job.slimming = slim_supports(surface, slimming);
  job.posed = surface;
  return job;
}

}  // namespace slim
