// Print Orientation, then Support Slimming in the pose it found: the job behind Support
// Slimming's "Optimize the orientation first" and the CLI's --orient, written once.
//
//   OrientedSlimming job = slim_in_best_pose(surface, slimming, orientation);
//
// Inputs
//   surface      the part as the user gave it (#V by 3 mm, #F by 3).
//   slimming     SlimmingOptions; its print direction is ignored (the search chooses it) and its
//                alpha_max is the search's too, so both steps judge overhangs by one rule.
//   orientation  OrientationOptions: the search effort and its other settings; its alpha_max,
//                plate tolerance and thread count are taken from `slimming`.
// Outputs (OrientedSlimming)
//   orientation  the search's result (orientation.h): the chosen direction, the best poses.
//   posed        the part turned rigidly into its print pose: +Z up, resting on z = 0.
//   slimming     Support Slimming of `posed` along +Z: its displacement and volume change count
//                the deformation alone, measured in that pose.
// The build plate rule: the search resolves it on the part as given (the automatic rule: 1e-3 of
// its size) and the slimming uses the same tolerance.
// The deviation budget: a share of the diagonal is of the part as given, turned into a length,
// so that the same part gets the same allowance whatever pose the search picks.
// Errors: those of optimize_orientation and slim_supports.
#pragma once

#include <optional>

#include "core/optimizer/slimming.h"
#include "core/orientation/orientation.h"

namespace slim {

struct OrientedSlimming {
  OrientationResult orientation;
  Surface posed;
  SlimmingResult slimming;
};

OrientedSlimming slim_in_best_pose(const Surface& surface, SlimmingOptions slimming, OrientationOptions orientation);

// The job as the user asked for it: slim_in_best_pose when `orientation` is given, else Support
// Slimming of the part as given (posed = surface, orientation left at its defaults).
OrientedSlimming slim_as_asked(const Surface& surface, const SlimmingOptions& slimming,
                               const std::optional<OrientationOptions>& orientation);

}  // namespace slim
