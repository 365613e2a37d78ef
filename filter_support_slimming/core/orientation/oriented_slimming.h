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
// The build plate tolerance: the one given (>= 0) serves both steps; a negative one lets the
// search choose its default (1e-3 of the part's size) and the slimming then uses the same.
// The deviation budget: a percentage is of the bbox diagonal of the part as given, turned into a
// length (max_deviation_mm), so that the same part gets the same allowance whatever pose the
// search picks.
// Errors: those of optimize_orientation and slim_supports.
#pragma once

#include "core/optimizer/slimming.h"
#include "core/orientation/orientation.h"

namespace slim {

struct OrientedSlimming {
  OrientationResult orientation;
  Surface posed;
  SlimmingResult slimming;
};

OrientedSlimming slim_in_best_pose(const Surface& surface, SlimmingOptions slimming, OrientationOptions orientation);

}  // namespace slim
