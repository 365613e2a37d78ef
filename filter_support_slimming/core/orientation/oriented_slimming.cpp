#include "core/orientation/oriented_slimming.h"

namespace slim {

OrientedSlimming slim_in_best_pose(const Surface& surface, SlimmingOptions slimming, OrientationOptions orientation) {
  orientation.alpha_max_deg = slimming.alpha_max_deg;
  orientation.plate_tolerance = slimming.plate_tolerance;
  orientation.threads = slimming.threads;
  OrientedSlimming job;
  job.orientation = optimize_orientation(surface, orientation);
  job.posed = apply_orientation(surface, job.orientation.rotation);
  slimming.print_direction = Eigen::Vector3d::UnitZ();
  // The budget is the user's: a share of the part as they gave it, a length that the turn does not
  // change (the posed part's bounding box is another one).
  if (slimming.max_deviation_mm <= 0.0 && slimming.max_deviation_pct > 0.0 && surface.V.rows() > 0)
    slimming.max_deviation_mm =
        slimming.max_deviation_pct / 100.0 * (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm();
  if (slimming.plate_tolerance < 0) slimming.plate_tolerance = job.orientation.plate_tolerance;
  job.slimming = slim_supports(job.posed, slimming);
  return job;
}

}  // namespace slim
