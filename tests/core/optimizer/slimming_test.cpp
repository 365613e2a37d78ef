// Invariants of the local/global optimizer: less risky area, nothing inverted, the base stays on
// the plate, the budget holds, rigid features stay rigid, and results repeat whatever the threads.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "core/optimizer/slimming.h"
#include "core/support_model/support_model.h"
#include "support/free_to_move.h"
#include "support/shapes.h"

using namespace slim;

// The sample bunny is read through VCG: a core-only build (no MeshLab sources) has these tests out.
#ifdef SLIM_TESTS_HAVE_VCG
namespace {
const Surface& bunny() { return test::sample_bunny(); }
double diag(const Surface& s) { return test::bbox_diagonal(s); }
}  // namespace

TEST(Slimming, BunnyLosesRiskyAreaWithoutInversionInsideTheBudget) {
  SlimmingOptions o;
  o.budget = DeviationBudget::from_percent(5.0);
  const SlimmingResult r = slim_supports(bunny(), o);
  EXPECT_LT(r.after.risky_area, 0.92 * r.before.risky_area);  // at least 8% less
  EXPECT_EQ(r.history.back().inverted_tets, 0);
  EXPECT_LE(r.displacement.maxCoeff(), 0.05 * diag(bunny()) * (1 + 1e-9));
  EXPECT_EQ(r.surface.F, bunny().F);  // topology unchanged
  // The base stays on the plate: nothing below it, and the lowest point is still on it.
  EXPECT_GE(r.surface.V.col(2).minCoeff(), bunny().V.col(2).minCoeff() - 1e-9);
  EXPECT_NEAR(r.surface.V.col(2).minCoeff(), bunny().V.col(2).minCoeff(), 1e-9);
  // The reported figures are those of the returned surface.
  const OverhangReport check = analyse_overhang(r.surface, {Eigen::Vector3d::UnitZ(), 45.0, PlateRule::within(1e-3 * diag(bunny()))});
  EXPECT_NEAR(check.risky_area, r.after.risky_area, 1e-9);
  EXPECT_NEAR(r.history.back().risky_area, r.after.risky_area, 1e-9);
}

TEST(Slimming, PaperMethodAlsoHelpsAndCoherentHelpsMore) {
  SlimmingOptions o;
  o.budget = DeviationBudget::from_percent(5.0);
  o.method = SlimmingMethod::Paper;
  const SlimmingResult paper = slim_supports(bunny(), o);
  o.method = SlimmingMethod::Coherent;
  const SlimmingResult coherent = slim_supports(bunny(), o);
  EXPECT_LT(paper.after.risky_area, 0.97 * paper.before.risky_area);
  EXPECT_LT(coherent.after.risky_area, paper.after.risky_area);
}

// What the default method is for: less support, as the support model counts what PrusaSlicer
// builds (support_model.h), than the paper's method saves, at every budget from 2% to 10%, with the
// volume kept. On the T and the mushroom the paper's method saves nothing (its bent-up arms and rim
// lift the overhangs that are left: more support); the coherent one must still save.
// eval/studies/frontier.sh measures the same with the real slicers on the corpus.
namespace {
double modelled_support(const Surface& s) { return estimate_support(s).volume_mm3; }

// The optimizers compared, not the choice of what to return: the least saving is off (the T's
// slimming saves 1-2% at the slicer's own grid phase, and by default comes back unchanged), and
// the part may stretch as the paper's method lets it (allow_stretch); slimming_shape_test.cpp
// checks what the default's holds on the shape cost.
void expect_more_support_saved_than_by_the_paper(const Surface& mesh) {
  const double before = modelled_support(mesh);
  for (double budget : {2.0, 3.0, 5.0, 10.0}) {
    SCOPED_TRACE("budget " + std::to_string(budget) + "%");
    SlimmingOptions o;
    o.result.min_support_saving_pct = 0.0;
    o.steps.max_iterations = 200;
    o.budget = DeviationBudget::from_percent(budget);
    o.method = SlimmingMethod::Paper;
    const SlimmingResult paper = slim_supports(mesh, o);
    o.method = SlimmingMethod::Coherent;
    allow_stretch(o);
    const SlimmingResult coherent = slim_supports(mesh, o);
    const double paper_saved = before - modelled_support(paper.surface);
    const double coherent_saved = before - modelled_support(coherent.surface);
    EXPECT_GT(coherent_saved, 0.02 * before);
    EXPECT_GT(coherent_saved, paper_saved);
    // The run's own figures are the model's, of the input and of the surface it returns.
    EXPECT_DOUBLE_EQ(coherent.support_before_mm3.value(), before);
    EXPECT_NEAR(coherent.support_after_mm3.value(), before - coherent_saved, 1e-9 * before);
    EXPECT_NEAR(coherent.shape.volume_result / coherent.shape.volume_input, 1.0, 0.02);  // the volume kept
    for (const IterationStats& st : coherent.history) EXPECT_EQ(st.inverted_tets, 0);
  }
}

}  // namespace

TEST(Slimming, CoherentSavesMoreSupportThanThePaperOnTheBunny) {
  expect_more_support_saved_than_by_the_paper(bunny());
}
TEST(Slimming, CoherentSavesMoreSupportThanThePaperOnTheT) {
  expect_more_support_saved_than_by_the_paper(test::refined(test::t_shape(), 4));
}
// The mushroom's flat cap bends at its rim, which saves 4% of its modelled support over the grid
// phases but 0.3% at the slicer's own phase for the part as placed (PrusaSlicer: +0.2%): less than
// the least saving worth a change of shape (3%), so the input comes back bit for bit and the
// stop reason says why. With any saving allowed the same run returns the slimmed part. The cap
// may stretch here: held to its proportions, its rim saves nothing at all.
TEST(Slimming, ASavingWithinTheModelsErrorLeavesTheInputAsItWas) {
  const Surface mushroom = test::refined(test::mushroom(), 2);
  const double least = ResultChoiceOptions{}.min_support_saving_pct;
  for (double budget : {2.0, 5.0, 10.0}) {
    SCOPED_TRACE("budget " + std::to_string(budget) + "%");
    SlimmingOptions o;
    allow_stretch(o);
    o.budget = DeviationBudget::from_percent(budget);
    const SlimmingResult kept = slim_supports(mushroom, o);
    EXPECT_EQ(kept.iterations, 0);
    EXPECT_GT(kept.iterations_run, 0);
    EXPECT_EQ(kept.surface.V, mushroom.V);
    EXPECT_EQ(kept.support_after_mm3.value(), kept.support_before_mm3.value());
    EXPECT_NE(kept.stop_reason.find("% worth a change of shape, so the input is returned unchanged"), std::string::npos)
        << kept.stop_reason;
    o.result.min_support_saving_pct = 0.0;
    const SlimmingResult any = slim_supports(mushroom, o);
    EXPECT_GT(any.iterations, 0);
    EXPECT_LT(any.support_after_mm3.value(), kept.support_before_mm3.value());
    EXPECT_GT(any.support_slicer_phase_after_mm3.value(), (1.0 - least / 100.0) * kept.support_slicer_phase_before_mm3.value());
    EXPECT_NEAR(any.support_after_mm3.value(), modelled_support(any.surface), 1e-9 * any.support_before_mm3.value());
  }
}
TEST(Slimming, CoherentSavesMoreSupportThanThePaperOnTheArch) {
  expect_more_support_saved_than_by_the_paper(test::refined(test::arch(), 3));
}

// The coherent method aims its local step further past alpha_max than the paper's 1 degree
// (PrusaSlicer's own threshold); StepOptions::margin_deg, when set, is the margin of either
// method, and the method's own, set explicitly, is the same run to the bit. Aimed further, the
// faces bent up clear the slicer's threshold: less risky area there (alpha_max - 1 degree from the
// vertical) and less modelled support than the same run aimed at the threshold itself.
TEST(Slimming, TheCoherentMethodAimsPastTheSlicersThreshold) {
  SlimmingOptions o;
  const double coherent_margin = *method_applied(o).steps.margin_deg;
  EXPECT_GT(coherent_margin, 1.0);
  o.method = SlimmingMethod::Paper;
  EXPECT_EQ(*method_applied(o).steps.margin_deg, 1.0);
  o.steps.margin_deg = 2.5;
  EXPECT_EQ(*method_applied(o).steps.margin_deg, 2.5);
  o = SlimmingOptions{};
  o.steps.margin_deg = 0.0;
  EXPECT_EQ(*method_applied(o).steps.margin_deg, 0.0);

  // One voxel resolution: the property holds run by run, and the ladder returns one rung's run
  // bit for bit (resolution_ladder_test.cpp), so its other rungs would only repeat it.
  SlimmingOptions one;
  one.ladder.multiples.clear();
  const SlimmingResult aimed_past = slim_supports(bunny(), one);
  o = one;
  o.steps.margin_deg = 1.0;
  const SlimmingResult at_threshold = slim_supports(bunny(), o);
  o.steps.margin_deg = coherent_margin;
  EXPECT_EQ(slim_supports(bunny(), o).surface.V, aimed_past.surface.V);
  const PrintSetup slicer{Eigen::Vector3d::UnitZ(), 44.0, PlateRule::within(1e-3 * diag(bunny()))};
  EXPECT_LT(analyse_overhang(aimed_past.surface, slicer).risky_area, analyse_overhang(at_threshold.surface, slicer).risky_area);
  ASSERT_TRUE(aimed_past.support_after_mm3.value() && at_threshold.support_after_mm3.value());
  EXPECT_LT(aimed_past.support_after_mm3.value(), at_threshold.support_after_mm3.value());
  EXPECT_EQ(aimed_past.support_before_mm3.value(), at_threshold.support_before_mm3.value());
}

TEST(Slimming, CoherentInversionGuardHoldsVerticesBackAndGoesOn) {
  // On the T at 10% with the earlier settings of the method (10-degree steps, risky tets ten times
  // stiffer, no volume kept, the shadow volume choosing, free to stretch and to move; the defaults
  // bend it too gently to get there) the bevels along the arms' edges squeeze the walls above them until a step would invert
  // tets there. The coherent guard puts those tets' vertices back and carries on, and later
  // iterates are better: the result comes after the first iteration held back.
  SlimmingOptions o = test::free_to_move();
  o.budget = DeviationBudget::from_percent(10.0);
  o.steps.max_step_deg = 10.0;
  o.coherence.risky_boost = 10.0;
  o.keep_volume = false;
  o.result.judge = ResultJudge::ShadowVolume;
  const Surface t = test::refined(test::t_shape(), 4);
  const SlimmingResult r = slim_supports(t, o);
  int first_held = 0;
  for (const IterationStats& st : r.history) {
    EXPECT_EQ(st.inverted_tets, 0) << st.iteration;
    if (st.held_back_vertices > 0 && first_held == 0) first_held = st.iteration;
  }
  ASSERT_GT(first_held, 0) << "no step needed the guard";
  EXPECT_GT(r.iterations, first_held);
  EXPECT_EQ(r.stop_reason.find("inverted"), std::string::npos) << r.stop_reason;
  EXPECT_LT(r.after.risky_area, 0.8 * r.before.risky_area);
  EXPECT_LE(r.displacement.maxCoeff(), 0.1 * diag(t) * (1 + 1e-9));
}

TEST(Slimming, NeverReturnsAPartThatNeedsMoreSupport) {
  // At 45 degrees the flat undersides of the T's arms and the mushroom's cap need 35-45 degrees of
  // rotation, more than a 5% budget allows for the whole underside: bending them up as a body
  // lifts the overhangs that are left, and PrusaSlicer then lays more support (docs/judge.md).
  // The result is the iterate that needs the least support: by the support model for the default
  // method, by the shadow volume for the paper's. No iterate may beat it by its own judge, nor the
  // input; a run that finds none hands back the input itself, untouched.
  const std::pair<const char*, Surface> cases[] = {{"T", test::refined(test::t_shape(), 3)},
                                                   {"mushroom", test::refined(test::mushroom(), 2)},
                                                   {"arch", test::refined(test::arch(), 3)},
                                                   {"bunny", bunny()}};
  for (const auto& [name, mesh] : cases)
    for (SlimmingMethod method : {SlimmingMethod::Paper, SlimmingMethod::Coherent}) {
      SCOPED_TRACE(std::string(name) + (method == SlimmingMethod::Paper ? " paper" : " coherent"));
      SlimmingOptions o;
      o.method = method;
      o.budget = DeviationBudget::from_percent(5.0);
      const SlimmingResult r = slim_supports(mesh, o);
      EXPECT_GT(r.before.shadow_volume, 0.0);
      EXPECT_LE(r.after.risky_area, r.before.risky_area);
      if (method == SlimmingMethod::Paper) {
        EXPECT_LE(r.after.shadow_volume, r.before.shadow_volume);
        for (const IterationStats& st : r.history) EXPECT_GE(st.shadow_volume, r.after.shadow_volume);
      } else {
        ASSERT_GT(r.support_before_mm3.value(), 0.0);
        EXPECT_NEAR(r.support_after_mm3.value(), modelled_support(r.surface), 1e-9 * r.support_before_mm3.value());
        // A result saves at least the least worth a change of shape, over the grid phases and at
        // the slicer's own; the mushroom's rim and the T's arms save less at the slicer's phase
        // (PrusaSlicer: +0.2% and +1.0%), and so does the arch's crown held to its height: they
        // come back unchanged; the bunny is slimmed.
        const double least = o.result.min_support_saving_pct / 100.0;
        const double phase_bar = (1.0 - least) * r.support_slicer_phase_before_mm3.value();
        for (const IterationStats& st : r.history)
          if (st.risky_area <= r.before.risky_area && st.support_slicer_phase.value() <= phase_bar) {
            EXPECT_GE(st.support_estimate.value(), r.support_after_mm3.value()) << st.iteration;
          }
        if (r.iterations > 0) {
          EXPECT_LE(r.support_after_mm3.value(), (1.0 - least) * r.support_before_mm3.value());
          EXPECT_LE(r.support_slicer_phase_after_mm3.value(), phase_bar);
        }
        EXPECT_EQ(r.iterations == 0, std::string(name) != "bunny") << r.stop_reason;
      }
      EXPECT_EQ(r.history.back().inverted_tets, 0);
      EXPECT_GE(r.surface.V.col(2).minCoeff(), -1e-9);  // nothing below the plate
      if (r.iterations == 0) {
        EXPECT_EQ(r.surface.V, mesh.V);  // the input itself, bit for bit
        EXPECT_EQ(r.displacement.maxCoeff(), 0.0);
      }
    }
}

TEST(Slimming, EveryGlobalStepMinimisesItsOwnEnergy) {
  for (SlimmingMethod method : {SlimmingMethod::Paper, SlimmingMethod::Coherent}) {
    SlimmingOptions o;
    o.method = method;
    o.budget = DeviationBudget::from_percent(0.0);  // no budget: keep every step
    o.steps.max_iterations = 8;
    o.steps.stall_tolerance = -1e300;
    const SlimmingResult r = slim_supports(bunny(), o);
    ASSERT_GT(r.history.size(), 1u);
    for (size_t i = 1; i < r.history.size(); ++i) {
      const IterationStats& st = r.history[i];
      EXPECT_LE(st.energy_solved, st.energy_start * (1 + 1e-12) + 1e-12) << "iteration " << i;
      EXPECT_GT(st.energy_start, 0.0);  // the local step asked for something new
    }
  }
}

TEST(Slimming, SafeMeshComesBackUnchanged) {
  const Surface cube = test::box({0, 0, 0}, {10, 10, 10});
  const SlimmingResult r = slim_supports(cube, {});
  EXPECT_EQ(r.iterations, 0);
  EXPECT_LE((r.surface.V - cube.V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(r.history.size(), 1u);
  EXPECT_EQ(r.shape.crease_share_pct, 0.0);  // unchanged: the shape paid nothing
  EXPECT_EQ(r.shape.volume_change_pct, 0.0);
  EXPECT_EQ(r.shape.interior_edges, 3 * 12 / 2);
}

TEST(Slimming, ZeroIterationsEmbedsAndWritesBack) {
  SlimmingOptions o;
  o.steps.max_iterations = 0;
  const SlimmingResult r = slim_supports(bunny(), o);
  EXPECT_EQ(r.surface.V, bunny().V);  // checked to round-trip, then handed back exactly
  EXPECT_EQ(r.after.risky_area, r.before.risky_area);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_NE(r.stop_reason.find("round trip within"), std::string::npos) << r.stop_reason;
}

TEST(Slimming, DeviationBudgetHoldsAtEveryLevel) {
  for (double budget : {1.0, 2.0, 3.0}) {
    SlimmingOptions o;
    o.budget = DeviationBudget::from_percent(budget);
    // One voxel resolution: the property holds run by run, and the ladder returns one rung's run
    // bit for bit (resolution_ladder_test.cpp), so its other rungs would only repeat it.
    o.ladder.multiples.clear();
    const SlimmingResult r = slim_supports(bunny(), o);
    EXPECT_LE(r.displacement.maxCoeff(), budget / 100.0 * diag(bunny()) * (1 + 1e-9)) << budget;
    EXPECT_LE(r.after.risky_area, r.before.risky_area);
  }
}

TEST(Slimming, SameResultWithOneAndTwoThreads) {
  // The bunny, and the T at 10%, whose run turns on edge directions and the inversion guard.
  for (const auto& [mesh, budget, iterations] :
       {std::tuple{bunny(), 5.0, 6}, std::tuple{test::refined(test::t_shape(), 4), 10.0, 40}}) {
    SlimmingOptions o;
    o.steps.max_iterations = iterations;
    o.budget = DeviationBudget::from_percent(budget);
    // One voxel resolution: the property holds run by run, and the ladder returns one rung's run
    // bit for bit (resolution_ladder_test.cpp), so its other rungs would only repeat it.
    o.ladder.multiples.clear();
    o.threads = 1;
    const SlimmingResult one = slim_supports(mesh, o);
    o.threads = 2;
    const SlimmingResult two = slim_supports(mesh, o);
    EXPECT_EQ(one.surface.V, two.surface.V);  // bit for bit
    ASSERT_EQ(one.history.size(), two.history.size());
    for (size_t i = 0; i < one.history.size(); ++i) {
      EXPECT_EQ(one.history[i].risky_area, two.history[i].risky_area);
      EXPECT_EQ(one.history[i].energy, two.history[i].energy);
      EXPECT_EQ(one.history[i].held_back_vertices, two.history[i].held_back_vertices);
    }
  }
}

TEST(Slimming, RigidFeatureKeepsItsShapeWhileTheRestBends) {
  // The feature: the bunny's head and ears (the top 30%), a large overhang-bearing region.
  const Surface& s = bunny();
  const double zmax = s.V.col(2).maxCoeff();
  std::vector<bool> feature(static_cast<size_t>(s.F.rows()), false);
  std::vector<int> feature_vertices;
  std::vector<bool> seen(static_cast<size_t>(s.V.rows()), false);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && s.V(s.F(f, k), 2) > 0.7 * zmax;
    feature[static_cast<size_t>(f)] = top;
    if (top)
      for (int k = 0; k < 3; ++k)
        if (!seen[static_cast<size_t>(s.F(f, k))]) {
          seen[static_cast<size_t>(s.F(f, k))] = true;
          feature_vertices.push_back(s.F(f, k));
        }
  }
  ASSERT_GT(feature_vertices.size(), 50u);
  SlimmingOptions o;
  o.budget = DeviationBudget::from_percent(5.0);
  o.rigid_features = feature;
  // One voxel resolution: the property holds run by run, and the ladder returns one rung's run
  // bit for bit (resolution_ladder_test.cpp), so its other rungs would only repeat it.
  o.ladder.multiples.clear();
  const SlimmingResult r = slim_supports(s, o);
  ASSERT_GT(r.iterations, 0);
  double worst = 0.0;
  for (size_t a = 0; a < feature_vertices.size(); a += 7)
    for (size_t b = a + 1; b < feature_vertices.size(); b += 5) {
      const double before = (s.V.row(feature_vertices[a]) - s.V.row(feature_vertices[b])).norm();
      const double after = (r.surface.V.row(feature_vertices[a]) - r.surface.V.row(feature_vertices[b])).norm();
      if (before > 0.05 * diag(s)) worst = std::max(worst, std::abs(after / before - 1.0));
    }
  EXPECT_LE(worst, 0.01);
  // The rest does bend: some unselected vertex moved by a clear amount.
  double moved = 0.0;
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    if (!seen[static_cast<size_t>(v)]) moved = std::max(moved, r.displacement(v));
  EXPECT_GT(moved, 1e-3 * diag(s));
}

TEST(Slimming, CancelStopsTheRun) {
  SlimmingOptions o;
  int calls = 0;
  o.progress = [&](double, const std::string&) { return ++calls < 3; };
  EXPECT_THROW(slim_supports(bunny(), o), Cancelled);
  EXPECT_EQ(calls, 3);
}

TEST(Slimming, BadInputIsRefusedWithAReason) {
  EXPECT_THROW(slim_supports(Surface{}, {}), std::invalid_argument);
  SlimmingOptions o;
  o.print.alpha_max_deg = -5;
  EXPECT_THROW(slim_supports(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.rigid_features = {true, false};
  EXPECT_THROW(slim_supports(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.resolution = 0;
  EXPECT_THROW(slim_supports(test::t_shape(), o), std::invalid_argument);
  for (double margin : {45.0, std::nan("")}) {
    o = {};
    o.steps.margin_deg = margin;
    EXPECT_THROW(slim_supports(test::t_shape(), o), std::invalid_argument) << margin;
  }
  o = {};
  o.steps.margin_deg = -1.0;
  EXPECT_THROW(slim_supports(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.result.min_support_saving_pct = 100.0;
  EXPECT_THROW(slim_supports(test::t_shape(), o), std::invalid_argument);
}
#endif  // SLIM_TESTS_HAVE_VCG
