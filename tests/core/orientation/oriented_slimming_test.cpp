// Orient, then slim (core/orientation/oriented_slimming.h): the deviation budget is the user's, a share of the
// part as given, whatever pose the search picks.
#include <gtest/gtest.h>

#include "core/geometry/surface_distance.h"
#include "core/orientation/oriented_slimming.h"
#include "support/shapes.h"

using namespace slim;

#ifdef SLIM_TESTS_HAVE_VCG
namespace {
double diag(const Points& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }
}  // namespace

TEST(OrientedSlimming, TheBudgetIsAShareOfThePartAsGiven) {
  const Surface bunny = test::load_mesh(test::sample_bunny_path());
  for (double pct : {2.0, 5.0}) {
    SlimmingOptions o;
    o.budget = DeviationBudget::from_percent(pct);
    // One voxel resolution: the property holds run by run, and the ladder returns one rung's run
    // bit for bit (resolution_ladder_test.cpp), so its other rungs would only repeat it.
    o.ladder.multiples.clear();
    // Any saving returns the result: the property is about the moves, so the run must move.
    o.result.min_support_saving_pct = 0.0;
    const OrientedSlimming job = slim_in_best_pose(bunny, o, with_effort(OrientationEffort::Fast));
    const double budget = pct / 100.0 * diag(bunny.V);
    // The pose changes the bounding box: a budget read from it would be another length.
    EXPECT_GT(std::abs(diag(job.posed.V) - diag(bunny.V)), 1e-3 * diag(bunny.V)) << "the pose keeps the box: no test";
    EXPECT_NEAR(job.slimming.deviation_budget_mm.value(), budget, 1e-9 * budget);
    // The slimming's displacement, measured in the pose against the oriented part, within it.
    ASSERT_EQ(job.slimming.surface.V.rows(), job.posed.V.rows());
    const double moved = (job.slimming.surface.V - job.posed.V).rowwise().norm().maxCoeff();
    EXPECT_LE(moved, budget * (1 + 1e-9)) << pct << "%";
    EXPECT_NEAR(job.slimming.displacement.maxCoeff(), moved, 1e-9 * budget);
    // And the Hausdorff distance of the slimming, which no vertex's move can exceed.
    EXPECT_LE(surface_distance(job.posed, job.slimming.surface).hausdorff_mm, budget * (1 + 1e-9)) << pct << "%";
    EXPECT_GT(job.slimming.iterations, 0) << pct << "%: " << job.slimming.stop_reason;
  }
}

// The plate is one length in every pose, the one Support Slimming takes without the search (1e-3
// of the bbox diagonal of the part as given): a part the search leaves as it is is slimmed as it is
// without the search (the corpus's duck, whose nearly flat underside the search once read with a
// shorter tolerance, came out with a third of the saving).
TEST(OrientedSlimming, ThePlateIsTheSameLengthWithAndWithoutTheSearch) {
  const Surface bunny = test::load_mesh(test::sample_bunny_path());
  SlimmingOptions o;
  // The plate is read before any run: one voxel resolution is enough.
  o.ladder.multiples.clear();
  const OrientedSlimming job = slim_in_best_pose(bunny, o, with_effort(OrientationEffort::Fast));
  const double tolerance = 1e-3 * diag(bunny.V);
  EXPECT_DOUBLE_EQ(job.orientation.plate_tolerance_mm.value(), tolerance);
  PrintSetup posed;
  posed.plate = PlateRule::within(tolerance);
  const OverhangReport in_pose = analyse_overhang(job.posed, posed);
  EXPECT_EQ(job.slimming.before.risky_count, in_pose.risky_count);
  EXPECT_DOUBLE_EQ(job.slimming.before.risky_area, in_pose.risky_area);
  // Without the search: the same default.
  SlimmingOptions none = o;
  none.steps.max_iterations = 0;
  PrintSetup given;
  given.plate = PlateRule::within(tolerance);
  EXPECT_DOUBLE_EQ(slim_supports(bunny, none).before.risky_area, analyse_overhang(bunny, given).risky_area);
}

TEST(OrientedSlimming, ALengthGivenStaysThatLength) {
  const Surface T = test::transformed(test::t_shape(), test::axis_angle(Eigen::Vector3d(1, 0, 0), 2.0));
  SlimmingOptions o;
  o.budget = DeviationBudget::length(1.5);
  const OrientedSlimming job = slim_in_best_pose(T, o, with_effort(OrientationEffort::Fast));
  EXPECT_EQ(job.slimming.deviation_budget_mm, 1.5);
  EXPECT_LE(job.slimming.displacement.maxCoeff(), 1.5 * (1 + 1e-9));
}
#endif
