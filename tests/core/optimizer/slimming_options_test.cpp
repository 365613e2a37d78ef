// The slimming options (core/optimizer/slimming_options.h): the deviation budget in mm, the method
// applied once, and the refusals of values out of range.
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/optimizer/slimming_options.h"

namespace slim {
namespace {

TEST(SlimmingOptions, TheBudgetIsAShareOfTheDiagonalALengthOrNone) {
  EXPECT_DOUBLE_EQ(DeviationBudget::share_of_diagonal(5.0).mm(200.0).value(), 10.0);
  EXPECT_EQ(DeviationBudget::length(1.5).mm(200.0).value(), 1.5);
  EXPECT_FALSE(DeviationBudget::none().mm(200.0).has_value());
  // The CLI's and the dialog's convention: 0 or less is none.
  EXPECT_FALSE(DeviationBudget::from_percent(0.0).mm(200.0).has_value());
  EXPECT_FALSE(DeviationBudget::from_percent(-3.0).mm(200.0).has_value());
  EXPECT_EQ(DeviationBudget::from_percent(2.0).share_percent().value(), 2.0);
  EXPECT_FALSE(DeviationBudget::length(2.0).share_percent().has_value());
  EXPECT_EQ(SlimmingOptions{}.budget.share_percent().value(), 5.0);
}

TEST(SlimmingOptions, ABadBudgetIsRefused) {
  for (const DeviationBudget& bad : {DeviationBudget::from_percent(std::nan("")),
                                     DeviationBudget::from_percent(std::numeric_limits<double>::infinity()),
                                     DeviationBudget::length(0.0), DeviationBudget::length(-1.0)})
    EXPECT_THROW(bad.validate(), std::invalid_argument);
  DeviationBudget::none().validate();
  DeviationBudget::share_of_diagonal(1e-6).validate();
}

TEST(SlimmingOptions, TheMethodIsAppliedOnce) {
  SlimmingOptions coherent;
  const SlimmingOptions c = method_applied(coherent);
  EXPECT_EQ(c.steps.margin_deg.value(), 10.0);
  EXPECT_EQ(c.steps.max_step_deg.value(), 2.0);
  EXPECT_EQ(c.coherence.risky_boost, coherent.coherence.risky_boost);
  EXPECT_EQ(c.result.judge, ResultJudge::SupportModel);
  EXPECT_EQ(c.ladder.multiples, coherent.ladder.multiples);

  SlimmingOptions paper;
  paper.method = SlimmingMethod::Paper;
  paper.steps.max_step_deg = 4.0;  // a cap given is either method's
  const SlimmingOptions p = method_applied(paper);
  EXPECT_EQ(p.steps.margin_deg.value(), 1.0);
  EXPECT_EQ(p.steps.max_step_deg.value(), 4.0);
  EXPECT_EQ(p.coherence.interior_weight, 1.0);
  EXPECT_EQ(p.coherence.risky_boost, 1.0);
  EXPECT_EQ(p.coherence.smoothing, 0.0);
  EXPECT_EQ(p.coherence.propagation, 0.0);
  EXPECT_FALSE(p.coherence.edge_turns);
  EXPECT_EQ(p.result.judge, ResultJudge::ShadowVolume);
  EXPECT_FALSE(p.result.max_crease_share_pct.has_value());
  EXPECT_EQ(p.result.min_support_saving_pct, 0.0);
  EXPECT_TRUE(p.ladder.multiples.empty());
  EXPECT_FALSE(p.keep_volume);
  EXPECT_FALSE(p.guards.local_inversion_guard);
  EXPECT_FALSE(p.guards.surface_guard);
  // The paper's method lets the part stretch and move as far as the budget allows.
  EXPECT_FALSE(p.hold_proportions);
  EXPECT_EQ(p.region.stiffness, 0.0);
  EXPECT_FALSE(p.guards.max_rise_pct.has_value());
  EXPECT_FALSE(p.result.max_mean_displacement_pct.has_value());
  EXPECT_TRUE(c.hold_proportions);
  EXPECT_GT(c.region.stiffness, 0.0);
  EXPECT_TRUE(c.guards.max_rise_pct.has_value());
  // Applying it again changes nothing.
  const SlimmingOptions twice = method_applied(p);
  EXPECT_EQ(twice.steps.margin_deg, p.steps.margin_deg);
  EXPECT_EQ(twice.steps.max_step_deg, p.steps.max_step_deg);
}

TEST(SlimmingOptions, ValuesOutOfRangeAreRefusedWithAReason) {
  auto reason = [](const SlimmingOptions& o) -> std::string {
    try {
      validate_slimming_options(o, 4);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(reason(SlimmingOptions{}), "");
  SlimmingOptions o;
  o.steps.margin_deg = 45.0;
  EXPECT_NE(reason(o).find("angular margin"), std::string::npos);
  o = {};
  o.steps.max_step_deg = 0.0;
  EXPECT_NE(reason(o).find("step cap"), std::string::npos);
  o = {};
  o.result.max_crease_share_pct = 0.0;  // none is std::nullopt, not 0
  EXPECT_NE(reason(o).find("crease share limit"), std::string::npos);
  o = {};
  o.guards.max_memory_bytes = -1.0;
  EXPECT_NE(reason(o).find("memory budget"), std::string::npos);
  o = {};
  o.result.max_mean_displacement_pct = -1.0;
  EXPECT_NE(reason(o).find("mean displacement limit"), std::string::npos);
  o = {};
  o.guards.max_rise_pct = 101.0;
  EXPECT_NE(reason(o).find("allowed rise"), std::string::npos);
  for (const double share : {0.0, 1.5, double(NAN)}) {
    o = {};
    o.coherence.costly_share = share;
    EXPECT_NE(reason(o).find("support cost whose overhangs are turned"), std::string::npos) << share;
  }
  o = {};
  o.region.stiffness = -1.0;
  EXPECT_NE(reason(o).find("anchoring stiffness"), std::string::npos);
  o = {};
  o.region.ramp_share = NAN;
  EXPECT_NE(reason(o).find("free region"), std::string::npos);
  o = {};
  o.rigid_features = {true, false};
  EXPECT_NE(reason(o).find("one entry per face"), std::string::npos);
  o = {};
  o.budget = DeviationBudget::length(-2.0);
  EXPECT_NE(reason(o).find("deviation budget"), std::string::npos);
}

}  // namespace
}  // namespace slim
