// Which iterate a run returns (result_choice.h): the least support, never more risky area than
// the input, never past the crease limit, and by the support model never a saving smaller than
// the least worth a change of shape.
#include <cmath>

#include <gtest/gtest.h>

#include "core/optimizer/result_choice.h"

namespace slim {
namespace {

// An iterate as the support model measured it; a NaN support: the model could not measure it.
IterationStats by_model(double support, double risky = 10.0, double creases = 0.0) {
  IterationStats s;
  if (!std::isnan(support)) s.support_estimate = support;
  s.shadow_volume = 1e6;  // never read when the model measures
  s.risky_area = risky;
  s.crease_share_pct = creases;
  return s;
}

TEST(IterateChoice, ASavingUnderTheLeastIsNotWorthAChangeOfShape) {
  IterateChoice choice(by_model(100.0), ResultJudge::SupportModel, std::nullopt, 3.0);
  EXPECT_FALSE(choice.offer(by_model(98.0)));  // 2% saved
  EXPECT_FALSE(choice.offer(by_model(97.5)));  // 2.5%
  EXPECT_NEAR(choice.best_unsaved_pct(), 2.5, 1e-12);
  EXPECT_TRUE(choice.offer(by_model(96.0)));   // 4%: worth it
  EXPECT_FALSE(choice.offer(by_model(96.5)));  // a saving, but less than the best's
  EXPECT_TRUE(choice.offer(by_model(90.0)));
}

TEST(IterateChoice, TheLeastSavingMustHoldAtTheSlicersOwnPhaseToo) {
  // The phase mean decides between iterates, but a saving it finds only at grid phases the slicer
  // does not lay for the part as placed is not worth a change of shape.
  auto at = [](double mean, double slicer_phase) {
    IterationStats s = by_model(mean);
    s.support_slicer_phase = slicer_phase;
    return s;
  };
  IterateChoice choice(at(100.0, 120.0), ResultJudge::SupportModel, std::nullopt, 3.0);
  EXPECT_FALSE(choice.offer(at(95.0, 119.0)));  // 5% over the phases, 0.8% at the slicer's
  EXPECT_NEAR(choice.best_unsaved_pct(), 100.0 / 120.0, 1e-12);
  EXPECT_FALSE(choice.offer(at(98.0, 100.0)));  // 2% and 17%: the mean falls short
  EXPECT_NEAR(choice.best_unsaved_pct(), 2.0, 1e-12);
  EXPECT_TRUE(choice.offer(at(96.0, 116.0)));   // 4% and 3.3%: both hold
  EXPECT_FALSE(choice.offer(at(90.0, 117.0)));  // more saved over the phases, too little at the slicer's
  EXPECT_TRUE(choice.offer(at(94.0, 110.0)));
  // Without the least, any saving over the phases counts, whatever the slicer's phase says.
  IterateChoice any(at(100.0, 120.0), ResultJudge::SupportModel, std::nullopt, 0.0);
  EXPECT_TRUE(any.offer(at(99.0, 125.0)));
}

TEST(IterateChoice, WithoutTheLeastAnySavingCounts) {
  IterateChoice choice(by_model(100.0), ResultJudge::SupportModel, std::nullopt, 0.0);
  EXPECT_TRUE(choice.offer(by_model(99.9)));
  EXPECT_FALSE(choice.offer(by_model(100.5)));
}

TEST(IterateChoice, TheLeastSavingIsTheModelsNotTheShadowVolumes) {
  // A run without the support model chooses by the shadow volume, whose figures are no slicer's:
  // the least saving is not read there.
  IterationStats input;
  input.shadow_volume = 100.0;
  input.risky_area = 10.0;
  IterateChoice choice(input, ResultJudge::ShadowVolume, std::nullopt, 3.0);
  IterationStats s = input;
  s.shadow_volume = 99.0;
  EXPECT_TRUE(choice.offer(s));
}

TEST(IterateChoice, NeitherMoreRiskyAreaNorCreasesNorAnUnmeasuredIterateQualify) {
  IterateChoice choice(by_model(100.0, 10.0), ResultJudge::SupportModel, 2.5, 3.0);
  EXPECT_FALSE(choice.offer(by_model(50.0, 10.5)));         // more risky area than the input
  EXPECT_FALSE(choice.offer(by_model(std::nan(""), 5.0)));  // the model could not measure it
  EXPECT_TRUE(choice.reads_creases(by_model(60.0)));
  EXPECT_FALSE(choice.reads_creases(by_model(98.0)));       // under the least saving: never chosen
  EXPECT_FALSE(choice.offer(by_model(60.0, 5.0, 2.6)));     // creased past the limit
  EXPECT_EQ(choice.passed_over(), 1);
  EXPECT_TRUE(choice.offer(by_model(70.0, 5.0, 2.4)));
}

}  // namespace
}  // namespace slim
