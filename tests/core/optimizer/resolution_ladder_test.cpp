// The resolution ladder (resolution_ladder.h): which voxel resolutions a run slims at, and that
// the result is exactly the run, among them, whose result the support model says needs the least
// support.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "core/optimizer/resolution_ladder.h"
#include "core/optimizer/support_slimmer.h"
#include "core/optimizer/slimming.h"
#include "support/free_to_move.h"
#include "support/shapes.h"

using namespace slim;

namespace {

// A part the rungs slim differently, and the middle one best: a bowl (the lower half of a
// sphere, open at the top; 160 faces), on a coarse ladder (12, 16 and 24 cells: the default
// multiples of 12) so that the sanitizer build runs it in seconds.
const Surface& bowl() {
  static const Surface s = test::open_hemisphere(2);
  return s;
}
constexpr int kBase = 12;

// The part free to move (test::free_to_move): so the bowl slims at every rung, best at the middle
// one, and the choice among the rungs is tested rather than the shape's limits.
SlimmingOptions laddered_options() {
  SlimmingOptions o = test::free_to_move();
  o.resolution = kBase;
  return o;
}

SlimmingOptions at_one_resolution(int resolution) {
  SlimmingOptions o = test::free_to_move();
  o.resolution = resolution;
  o.ladder.multiples.clear();
  return o;
}

// The runs, each made once per test: the ladder from 12 cells, and each rung alone.
const SlimmingResult& laddered() {
  static const SlimmingResult r = slim_supports(bowl(), laddered_options());
  return r;
}
const SlimmingResult& alone(int resolution) {
  static std::map<int, SlimmingResult> runs;
  auto it = runs.find(resolution);
  if (it == runs.end()) it = runs.emplace(resolution, slim_supports(bowl(), at_one_resolution(resolution))).first;
  return it->second;
}

}  // namespace

TEST(ResolutionLadder, TheRungsAreTheResolutionThenItsMultiples) {
  SlimmingOptions o;
  EXPECT_EQ(ladder_resolutions(o, 1000), (std::vector<int>{24, 32, 48}));
  o.resolution = 10;
  EXPECT_EQ(ladder_resolutions(o, 1000), (std::vector<int>{10, 13, 20}));  // 13.33 rounds to 13
  o.ladder.multiples = {1.04, 2.0, 2.01};  // 10.4 -> 10 and 20.1 -> 20 repeat a rung
  EXPECT_EQ(ladder_resolutions(o, 1000), (std::vector<int>{10, 20}));
  // Off: one rung, the resolution given.
  const SlimmingOptions defaults;
  auto only_the_resolution = [](const SlimmingOptions& off, long faces) {
    EXPECT_EQ(ladder_resolutions(off, faces), std::vector<int>{off.resolution});
  };
  only_the_resolution(defaults, defaults.ladder.max_faces + 1);  // too large
  EXPECT_EQ(ladder_resolutions(defaults, defaults.ladder.max_faces).size(), 3u);
  o = defaults;
  o.method = SlimmingMethod::Paper;  // the paper as written: one resolution
  only_the_resolution(o, 1000);
  o = defaults;
  o.domain = DomainKind::TetGen;  // no voxels
  only_the_resolution(o, 1000);
  o = defaults;
  o.result.judge = ResultJudge::ShadowVolume;  // nothing to choose by
  only_the_resolution(o, 1000);
  o = defaults;
  o.steps.max_iterations = 0;  // embed and write back only
  only_the_resolution(o, 1000);
  o = defaults;
  o.ladder.multiples.clear();
  only_the_resolution(o, 1000);
}

TEST(ResolutionLadder, BadMultiplesAreRefusedWithAReason) {
  for (double bad : {1.0, 0.5, 4.5, -2.0}) {
    SlimmingOptions o;
    o.ladder.multiples = {bad};
    try {
      slim_supports(bowl(), o);
      ADD_FAILURE() << "a multiple of " << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("multiples must be in (1, 4]"), std::string::npos) << e.what();
    }
  }
}

// Brute force: each rung run on its own. The ladder's result is, bit for bit, the one among them
// whose result has the least support estimate (the first on a tie), and it never needs more
// support than the resolution given alone.
TEST(ResolutionLadder, TheResultIsTheRungWhoseResultNeedsTheLeastSupport) {
  const SlimmingResult& r = laddered();
  const std::vector<int> rungs = ladder_resolutions(laddered_options(), static_cast<long>(bowl().F.rows()));
  ASSERT_EQ(rungs, (std::vector<int>{12, 16, 24}));
  ASSERT_EQ(r.resolution_runs.size(), rungs.size());
  size_t least = 0;
  for (size_t i = 0; i < rungs.size(); ++i) {
    EXPECT_EQ(r.resolution_runs[i].resolution, rungs[i]);
    EXPECT_TRUE(r.resolution_runs[i].refused.empty());
    EXPECT_EQ(r.resolution_runs[i].support_after_mm3.value(), alone(rungs[i]).support_after_mm3.value());
    EXPECT_EQ(r.resolution_runs[i].iterations, alone(rungs[i]).iterations);
    if (alone(rungs[i]).support_after_mm3.value() < alone(rungs[least]).support_after_mm3.value()) least = i;
  }
  // Neither the first rung nor the last wins here, so the test tells a choice from a rule of
  // thumb (take the given, or the finest).
  ASSERT_EQ(least, 1u) << "the bowl no longer slims best at the middle rung: choose another part";
  const SlimmingResult& best = alone(rungs[least]);
  EXPECT_EQ(r.resolution, rungs[least]);
  EXPECT_EQ(r.surface.V, best.surface.V);
  EXPECT_EQ(r.support_after_mm3.value(), best.support_after_mm3.value());
  EXPECT_EQ(r.support_slicer_phase_after_mm3.value(), best.support_slicer_phase_after_mm3.value());
  EXPECT_EQ(r.iterations, best.iterations);
  EXPECT_EQ(r.domain_tets, best.domain_tets);
  EXPECT_EQ(r.shape.crease_share_pct, best.shape.crease_share_pct);
  EXPECT_LT(r.support_after_mm3.value(), alone(rungs[0]).support_after_mm3.value());
  EXPECT_LT(r.support_after_mm3.value(), r.support_before_mm3.value());
  // The time is every rung's, not the chosen (middle) rung's alone, which is about a fifth of the
  // sum: the bound leaves room for the machine's load, which moves the separate runs' times.
  double seconds = 0.0;
  for (int resolution : rungs) seconds += alone(resolution).seconds;
  EXPECT_GT(r.seconds, 0.35 * seconds);
}

// A finer rung that the memory budget refuses is left out and said so; the resolution given is
// still refused as before (the run's own error).
TEST(ResolutionLadder, ARungOverTheMemoryBudgetIsLeftOutAndSaidSo) {
  const double needs_middle = optimizer_bytes(alone(16).domain_tets, alone(16).domain_vertices);
  const double needs_finest = optimizer_bytes(alone(24).domain_tets, alone(24).domain_vertices);
  ASSERT_LT(needs_middle, needs_finest);
  SlimmingOptions o = laddered_options();
  o.guards.max_memory_bytes = 0.5 * (needs_middle + needs_finest);
  const SlimmingResult r = slim_supports(bowl(), o);
  ASSERT_EQ(r.resolution_runs.size(), 3u);
  EXPECT_TRUE(r.resolution_runs[0].refused.empty());
  EXPECT_TRUE(r.resolution_runs[1].refused.empty());
  EXPECT_NE(r.resolution_runs[2].refused.find("memory budget"), std::string::npos) << r.resolution_runs[2].refused;
  EXPECT_EQ(r.resolution, 16);
  EXPECT_EQ(r.surface.V, alone(16).surface.V);
  EXPECT_NE(ladder_line(r).find(", 24 (not run: too large for the memory budget)"), std::string::npos) << ladder_line(r);
  o.guards.max_memory_bytes = 0.5 * needs_middle;  // under what the first rung needs
  o.resolution = 16;
  EXPECT_THROW(slim_supports(bowl(), o), std::invalid_argument);
}

// What the summary and the log say: the resolution, then each rung's estimate.
TEST(ResolutionLadder, TheLineNamesTheResolutionAndEachRungsEstimate) {
  const SlimmingResult& r = laddered();
  const std::string line = ladder_line(r);
  EXPECT_EQ(line.rfind(std::to_string(r.resolution) + " cells along the longest side; the least support of 12 (", 0), 0u) << line;
  for (const ResolutionRun& run : r.resolution_runs)
    EXPECT_NE(line.find(std::to_string(run.resolution) + " ("), std::string::npos) << line;
  EXPECT_EQ(ladder_line(alone(24)), "24 cells along the longest side");
}
