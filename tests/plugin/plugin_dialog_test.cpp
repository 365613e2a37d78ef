// Support Slimming's dialog parameters as MeshLab 2020.09 passes them (the deviation budget as an
// absolute-or-percentage value, the crease limit, the least saving) and the result layer's vertex
// colours, which show how far each vertex moved.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/optimizer/slimming_options.h"
#include "filter_checks.h"
#include "harness.h"
#include "support/shapes.h"

using namespace slim;
using slim::test::PluginHarness;
using slim::test::positions;

namespace {
const QString kSlimming = "Support Slimming";

std::vector<vcg::Color4b> vertex_colours(const MeshModel& m) {
  std::vector<vcg::Color4b> c;
  for (const CVertexO& v : m.cm.vert) c.push_back(v.cC());
  return c;
}

}  // namespace

// The budget is MeshLab's absolute-or-percentage parameter: its value is in mm, its percentage is
// of the bbox diagonal (the widget's range), and its default is the core's default share.
TEST(PluginDialog, TheBudgetIsAnAbsoluteOrPercentageValue) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  const double diag = input->cm.bbox.Diag();
  RichParameterList params = h.defaults(kSlimming, md);
  const auto* budget = dynamic_cast<const RichAbsPerc*>(&params.getParameterByName("maxDeviation"));
  ASSERT_NE(budget, nullptr) << params.getParameterByName("maxDeviation").stringType().toStdString();
  EXPECT_EQ(budget->stringType().toStdString(), "RichAbsPerc");
  EXPECT_FLOAT_EQ(budget->min, 0.0f);
  EXPECT_FLOAT_EQ(budget->max, float(diag));
  EXPECT_FLOAT_EQ(params.getAbsPerc("maxDeviation"), float(*SlimmingOptions().budget.mm(diag)));

  // 2 mm typed as such, and the percentage of the range that the widget turns into the same value.
  const float mm = 0.02f * float(diag);
  params.setValue("maxDeviation", AbsPercValue(mm));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  const auto absolute = positions(*md.mm());
  const QString log = h.logLines().join("\n");
  EXPECT_TRUE(log.contains(QString::asprintf("budget %.4g mm (2%% of the bbox diagonal)", double(mm)))) << log.toStdString();
  float moved = 0.0f;
  for (const CVertexO& v : md.mm()->cm.vert) moved = std::max(moved, float(v.cQ()));
  EXPECT_GT(moved, 0.0f);
  EXPECT_LE(moved, mm * 1.0001f);

  md.setCurrentMesh(input->id());
  const float percent = 2.0f;
  params.setValue("maxDeviation", AbsPercValue(budget->min + percent / 100.0f * (budget->max - budget->min)));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  EXPECT_EQ(positions(*md.mm()), absolute);
}

TEST(PluginDialog, CreaseLimitAndLeastSavingDefaultToTheCoresAndAreRangeChecked) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  test::add_layer(md, test::t_shape(), "T");
  const RichParameterList defaults = h.defaults(kSlimming, md);
  const ResultChoiceOptions core;
  EXPECT_FLOAT_EQ(defaults.getFloat("maxCreases"), float(core.max_crease_share_pct.value_or(0.0)));
  EXPECT_FLOAT_EQ(defaults.getFloat("minSaving"), float(core.min_support_saving_pct));
  struct Bad {
    const char* name;
    float value;
    const char* message;
  };
  for (const Bad& bad : {Bad{"maxCreases", -1.0f, "the crease limit must be in [0, 100] %"},
                         Bad{"maxCreases", 100.5f, "the crease limit must be in [0, 100] %"},
                         Bad{"minSaving", -0.5f, "the least saving must be in [0, 100) %"},
                         Bad{"minSaving", 100.0f, "the least saving must be in [0, 100) %"}}) {
    RichParameterList params = defaults;
    params.setValue(bad.name, FloatValue(bad.value));
    EXPECT_FALSE(h.apply(kSlimming, md, params)) << bad.name;
    EXPECT_TRUE(h.lastError().contains(bad.message)) << h.lastError().toStdString();
    EXPECT_TRUE(h.logLines().join("\n").contains(bad.message)) << bad.name;
    EXPECT_EQ(md.meshList.size(), 1) << bad.name;
  }
}

TEST(PluginDialog, ALeastSavingOf99PercentReturnsTheInputUnchangedWithTheReason) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("minSaving", FloatValue(99.0f));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  ASSERT_EQ(md.meshList.size(), 2);
  EXPECT_EQ(positions(*md.mm()), positions(*input));
  const QString log = h.logLines().join("\n");
  EXPECT_TRUE(log.contains("so the input is returned unchanged")) << log.toStdString();
}

TEST(PluginDialog, TheCreaseLimitReachesTheChoiceOfResult) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("minSaving", FloatValue(0.0f));
  params.setValue("maxCreases", FloatValue(0.01f));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  const QString tight = h.logLines().join("\n");
  EXPECT_TRUE(tight.contains("crease limit 0.01% of the edge length, least saving 0%")) << tight.toStdString();
  EXPECT_TRUE(tight.contains("creased more than the limit (0.01% of the edge length)")) << tight.toStdString();
}

// Blue where a vertex did not move, red at the budget: VCG's ramp of the displacement, which is the
// vertex quality; the layer shows the colours (MM_VERTCOLOR) when the input has none.
TEST(PluginDialog, TheSlimmedLayersVertexColoursShowTheDisplacement) {
  const float budget_mm = 2.0f;
  EXPECT_EQ(vcg::Color4b::ColorRamp(budget_mm, 0.0f, 0.0f), vcg::Color4b(vcg::Color4b::Blue));
  EXPECT_EQ(vcg::Color4b::ColorRamp(budget_mm, 0.0f, budget_mm), vcg::Color4b(vcg::Color4b::Red));

  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  ASSERT_FALSE(input->hasDataMask(MeshModel::MM_VERTCOLOR));
  const RichParameterList params = h.defaults(kSlimming, md);
  const float budget = params.getAbsPerc("maxDeviation");
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  const MeshModel& out = *md.mm();
  ASSERT_TRUE(out.hasDataMask(MeshModel::MM_VERTCOLOR));
  ASSERT_TRUE(out.hasDataMask(MeshModel::MM_VERTQUALITY));
  const auto by_quality = [](const CVertexO& a, const CVertexO& b) { return a.cQ() < b.cQ(); };
  const CVertexO& least = *std::min_element(out.cm.vert.begin(), out.cm.vert.end(), by_quality);
  const CVertexO& most = *std::max_element(out.cm.vert.begin(), out.cm.vert.end(), by_quality);
  EXPECT_LT(least.cQ(), 0.05f * budget);
  EXPECT_GT(least.cC()[2], 200) << "blue-ish where nothing moved";
  EXPECT_LT(least.cC()[0], 60);
  EXPECT_GT(most.cQ(), 0.2f * budget);
  EXPECT_EQ(most.cC(), vcg::Color4b::ColorRamp(budget, 0.0f, float(most.cQ())));
  for (const CVertexO& v : out.cm.vert) ASSERT_EQ(v.cC(), vcg::Color4b::ColorRamp(budget, 0.0f, float(v.cQ())));
  EXPECT_FALSE(input->hasDataMask(MeshModel::MM_VERTCOLOR)) << "the input layer is not changed";
}

TEST(PluginDialog, InputVertexColoursPassThroughBitForBit) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  input->updateDataMask(MeshModel::MM_VERTCOLOR);
  int k = 0;
  for (CVertexO& v : input->cm.vert) {
    v.C() = vcg::Color4b((k * 37) % 256, (k * 11) % 256, (k * 101) % 256, 255 - k % 7);
    ++k;
  }
  const auto original = vertex_colours(*input);
  ASSERT_TRUE(h.apply(kSlimming, md, h.defaults(kSlimming, md))) << h.lastError().toStdString();
  ASSERT_NE(md.mm(), input);
  EXPECT_TRUE(md.mm()->hasDataMask(MeshModel::MM_VERTCOLOR));
  EXPECT_EQ(vertex_colours(*md.mm()), original);
  EXPECT_NE(positions(*md.mm()), positions(*input)) << "the part moved, so the colours were kept by choice";
}
