// The plugin built for MeshLab 2022.02, loaded with QPluginLoader and run the way that MeshLab
// runs filters, on the sample bunny. The invariants are those of the 2020.09 harness
// (tests/plugin/plugin_test.cpp): MeshLab accepts the plugin, Overhang Analysis writes quality,
// colour and selection without moving a vertex, Support Slimming adds a new layer with less risky
// area and leaves the input alone, Print Orientation adds the part in its best pose as a new layer,
// and every refusal says why, in the error and in the log, with
// the document untouched. Only the API differs: errors arrive as MLException.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <vector>

#include <QRegularExpression>

#include <common/plugins/meshlab_plugin_type.h>
#include <common/plugins/plugin_manager.h>

#include "core/optimizer/slimming_options.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "core/support_model/support_model.h"
#include "filter_checks.h"
#include "harness.h"
#include "meshlab_api.h"
#include "support/shapes.h"
#include "vcg_adapters/surface_adapter.h"

using namespace slim;
using slim::test::PluginHarness;
using slim::test::positions;

namespace {
const QString kOverhang = "Overhang Analysis";
const QString kSlimming = "Support Slimming";
const QString kOrientation = "Print Orientation";

}  // namespace

// Every test starts with the plugin loaded and an empty document.
class Plugin2022 : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(h.ok()) << h.error().toStdString(); }
  MeshModel* add_bunny() { return test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny"); }

  PluginHarness h;
  MeshDocument md;
};

TEST_F(Plugin2022, MeshLabAcceptsThePlugin) {
  // MeshLab's own check before it loads a plugin, compiled into libmeshlab-common.so with that
  // MeshLab's version: a Qt plugin, a MeshLab plugin, the same version and precision, every filter
  // with a class and an arity. It throws MLException with the reason otherwise.
  try {
    EXPECT_TRUE(PluginManager::checkPlugin(SLIM_PLUGIN_PATH).isFilterPlugin());
  } catch (const MLException& e) {
    FAIL() << e.what();
  }

  EXPECT_EQ(h.plugin()->getMLVersion().first, SLIM_BUILT_FOR_MESHLAB);  // ML_VERSION of the sources
  EXPECT_FALSE(h.plugin()->getMLVersion().second);  // float, like Debian's MeshLab
  const QJsonObject meta = h.metaData();
  EXPECT_EQ(meta.value("name").toString(), "Support Slimming");
  EXPECT_EQ(meta.value("license").toString(), "GPL-3.0-or-later");
  EXPECT_EQ(meta.value("meshlabVersion").toString(), SLIM_BUILT_FOR_MESHLAB);
  for (const QString& name : {kOverhang, kSlimming, kOrientation}) {
    const QAction* a = h.action(name);
    ASSERT_NE(a, nullptr) << name.toStdString();
    EXPECT_NE(h.plugin()->getClass(a), FilterPlugin::Generic);
    EXPECT_EQ(h.plugin()->filterArity(a), FilterPlugin::SINGLE_MESH);
    EXPECT_FALSE(h.plugin()->filterInfo(a).isEmpty());
    // PyMeshLab's name, in the style of its own filters.
    EXPECT_TRUE(QRegularExpression("^(compute|generate)_[a-z_]+$").match(h.plugin()->pythonFilterName(a)).hasMatch())
        << h.plugin()->pythonFilterName(a).toStdString();
  }
}

TEST_F(Plugin2022, OverhangAnalysisMarksTheBunnysRiskyFacesAndMovesNothing) {
  MeshModel* m = add_bunny();
  const auto original = positions(*m);
  const RichParameterList params = h.defaults(kOverhang, md);
  ASSERT_TRUE(h.apply(kOverhang, md, params)) << h.lastError().toStdString();

  PrintSetup o;
  o.plate = PlateRule::within(params.getAbsPerc("plateTolerance"));
  const OverhangReport expected = analyse_overhang(vcg_adapters::to_surface(m->cm), o);
  ASSERT_GT(expected.risky_count, 0);  // the bunny's chin and ears overhang
  EXPECT_EQ(positions(*m), original);
  EXPECT_EQ(md.meshNumber(), 1u);
  test::expect_overhang_written(*m, expected);
  // The named results MeshLab 2022.02 (and pymeshlab) hand back.
  ASSERT_EQ(h.outputs().count("risky_area"), 1u);
  EXPECT_NEAR(h.outputs().at("risky_area").toDouble(), expected.risky_area, 1e-6 * expected.total_area);
  EXPECT_EQ(h.outputs().at("risky_faces").toLongLong(), expected.risky_count);
  EXPECT_TRUE(h.logLines().join("\n").contains("risky area")) << h.logLines().join("\n").toStdString();
}

TEST_F(Plugin2022, SupportSlimmingAddsASlimmedLayerAndLeavesTheInputAlone) {
  MeshModel* input = add_bunny();
  const auto original = positions(*input);
  const int input_mask = input->dataMask();
  const RichParameterList params = h.defaults(kSlimming, md);
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();

  ASSERT_EQ(md.meshNumber(), 2u);
  EXPECT_EQ(input->dataMask(), input_mask);
  test::expect_slimmed_layer(*input, *md.mm(), original, params.getAbsPerc("plateTolerance"), h.logLines());
  EXPECT_LT(h.outputs().at("risky_area_after").toDouble(), h.outputs().at("risky_area_before").toDouble());
}

// The budget is this API's absolute-or-percentage parameter (RichAbsPerc, RichPercentage from
// 2023.12 on) in mm, defaulting to the core's share of the bbox diagonal; the slimmed layer's
// vertex colours are VCG's ramp of the displacement, blue unmoved to red at the budget.
TEST_F(Plugin2022, TheBudgetIsAnAbsoluteOrPercentageValueAndTheColoursShowTheMove) {
  MeshModel* input = add_bunny();
  const RichParameterList params = h.defaults(kSlimming, md);
  const RichParameter& budget = params.getParameterByName("maxDeviation");
  EXPECT_NE(dynamic_cast<const meshlab_api::RichAbsPerc*>(&budget), nullptr) << budget.stringType().toStdString();
  const double budget_mm = params.getAbsPerc("maxDeviation");
  EXPECT_NEAR(budget_mm, *SlimmingOptions().budget.mm(input->cm.bbox.Diag()), 1e-6 * budget_mm);
  EXPECT_EQ(params.getFloat("maxCreases"), Scalarm(ResultChoiceOptions().max_crease_share_pct.value_or(0.0)));
  EXPECT_EQ(params.getFloat("minSaving"), Scalarm(ResultChoiceOptions().min_support_saving_pct));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  const MeshModel& out = *md.mm();
  ASSERT_TRUE(out.hasDataMask(MeshModel::MM_VERTCOLOR));
  Scalarm most = 0;
  for (const CVertexO& v : out.cm.vert) {
    ASSERT_EQ(v.cC(), vcg::Color4b::ColorRamp(float(budget_mm), 0.0f, float(v.cQ())));
    most = std::max(most, v.cQ());
  }
  EXPECT_GT(most, 0);
  EXPECT_LE(most, budget_mm * 1.0001);
  EXPECT_FALSE(input->hasDataMask(MeshModel::MM_VERTCOLOR));
}

TEST_F(Plugin2022, BadParametersFailWithTheirReasonAndTouchNothing) {
  MeshModel* m = add_bunny();
  const auto original = positions(*m);
  const int mask = m->dataMask();
  struct Case {
    const char* what;
    QString filter;
    std::function<void(RichParameterList&)> spoil;
    QString reason;  // must appear in the MLException and in the log
  };
  const std::vector<Case> cases = {
      {"angle out of range", kOverhang, [](RichParameterList& p) { p.setValue("alphaMax", FloatValue(95.0f)); }, "[0, 90)"},
      {"no print direction", kOverhang,
       [](RichParameterList& p) { p.setValue("printDirection", meshlab_api::Point3Value(vcg::Point3f(0, 0, 0))); }, "print direction"},
      {"enum out of range", kSlimming, [](RichParameterList& p) { p.setValue("method", IntValue(7)); }, "must be one of 0..1"},
      {"memory guard", kSlimming, [](RichParameterList& p) { p.setValue("resolution", IntValue(100000)); }, "resolution"},
      {"rigid features without a selection", kSlimming,
       [](RichParameterList& p) { p.setValue("preserveSelection", BoolValue(true)); }, "no face is selected"},
      {"negative budget", kSlimming, [](RichParameterList& p) { p.setValue("maxDeviation", FloatValue(-1.0f)); },
       "the deviation budget must be >= 0 mm"},
      {"crease limit over 100%", kSlimming, [](RichParameterList& p) { p.setValue("maxCreases", FloatValue(101.0f)); },
       "the crease limit must be in [0, 100] %"},
      {"negative least saving", kSlimming, [](RichParameterList& p) { p.setValue("minSaving", FloatValue(-1.0f)); },
       "the least saving must be in [0, 100) %"},
  };
  for (const Case& c : cases) {
    RichParameterList params = h.defaults(c.filter, md);
    c.spoil(params);
    EXPECT_FALSE(h.apply(c.filter, md, params)) << c.what;
    EXPECT_TRUE(h.lastError().startsWith(c.filter + ": ")) << h.lastError().toStdString();
    EXPECT_TRUE(h.lastError().contains(c.reason)) << c.what << ": " << h.lastError().toStdString();
    EXPECT_TRUE(h.logLines().join("\n").contains(h.lastError())) << c.what;
    EXPECT_EQ(md.meshNumber(), 1u) << c.what;
    EXPECT_EQ(md.mm(), m) << c.what;
    EXPECT_EQ(positions(*m), original) << c.what;
    EXPECT_EQ(m->dataMask(), mask) << c.what;
  }
}

TEST_F(Plugin2022, AScriptMissingAParameterIsRefusedByName) {
  add_bunny();
  const RichParameterList defaults = h.defaults(kOverhang, md);
  RichParameterList partial;
  for (const RichParameter& p : defaults)
    if (p.name() != "alphaMax") partial.addParam(p);
  EXPECT_FALSE(h.apply(kOverhang, md, partial));
  EXPECT_TRUE(h.lastError().contains("'alphaMax'")) << h.lastError().toStdString();
  EXPECT_TRUE(h.lastError().contains("missing")) << h.lastError().toStdString();
}

TEST_F(Plugin2022, OurExampleScriptsRunThroughMeshLab2022sParser) {
  // examples/*.mlx were written for 2020.09, whose RichPoint3f 2022.02 reads as a RichPosition.
  for (const auto& [file, filter] : {std::make_pair(QString("overhang_analysis.mlx"), kOverhang),
                                     std::make_pair(QString("support_slimming.mlx"), kSlimming),
                                     std::make_pair(QString("print_orientation.mlx"), kOrientation)}) {
    MeshDocument doc;
    test::add_layer(doc, test::t_shape(), "T");
    const RichParameterList scripted = test::example_script_params(file, filter);
    EXPECT_EQ(scripted.size(), h.defaults(filter, doc).size()) << file.toStdString();
    EXPECT_TRUE(h.apply(filter, doc, scripted)) << file.toStdString() << ": " << h.lastError().toStdString();
  }
}

TEST_F(Plugin2022, APointCloudFailsWithAClearMessage) {
  MeshModel* m = md.addNewMesh(QString(), "cloud", true);
  vcg::tri::Allocator<CMeshO>::AddVertices(m->cm, 3);
  for (const QString& filter : {kOverhang, kSlimming, kOrientation}) {
    EXPECT_FALSE(h.apply(filter, md, h.defaults(filter, md)));
    EXPECT_TRUE(h.lastError().contains("no faces")) << h.lastError().toStdString();
    EXPECT_EQ(md.meshNumber(), 1u);
  }
  EXPECT_EQ(m->cm.vn, 3);
}

TEST_F(Plugin2022, CancelLeavesNoHalfBuiltLayer) {
  MeshModel* input = add_bunny();
  const auto original = positions(*input);
  test::progress_reports = 0;
  EXPECT_FALSE(h.apply(kSlimming, md, h.defaults(kSlimming, md), test::cancel_at_second_report));
  EXPECT_GE(test::progress_reports, 2);
  EXPECT_TRUE(h.lastError().contains("cancelled")) << h.lastError().toStdString();
  EXPECT_EQ(md.meshNumber(), 1u);
  EXPECT_EQ(md.mm(), input);
  EXPECT_EQ(positions(*input), original);
}

TEST_F(Plugin2022, PrintOrientationTurnsTheBunnyIntoItsBestPoseAsANewLayer) {
  // The bunny turned on its back: the new layer holds it in the core's best pose, with less support
  // than it came with; the input layer stays as it was.
  MeshModel* input = test::add_layer(
      md, test::transformed(test::load_mesh(test::sample_bunny_path()), test::axis_angle({1, 0, 0}, M_PI), {0, 0, 0}),
      "bunny");
  const auto original = positions(*input);
  const RichParameterList params = h.defaults(kOrientation, md);
  ASSERT_TRUE(h.apply(kOrientation, md, params)) << h.lastError().toStdString();
  ASSERT_EQ(md.meshNumber(), 2u);
  OrientationOptions options = with_effort(OrientationEffort::Normal);
  options.alpha_max_deg = params.getFloat("alphaMax");
  test::expect_oriented_layer(*input, *md.mm(), original, options, h.logLines());
  // The pose is the support model's choice: less support by its estimate, which is the model's own
  // figure for each layer (the proxies may rise: on its back the bunny has less risky area).
  const double before = h.outputs().at("support_estimate_before_mm3").toDouble();
  const double after = h.outputs().at("support_estimate_after_mm3").toDouble();
  EXPECT_LT(after, before);
  EXPECT_NEAR(before, estimate_support(vcg_adapters::to_surface(input->cm)).volume_mm3, 1e-6 * before);
  EXPECT_NEAR(after, estimate_support(vcg_adapters::to_surface(md.mm()->cm)).volume_mm3, 2e-2 * before);  // float positions
}

TEST_F(Plugin2022, PrintOrientationRefusesBadSettingsAndAddsNothing) {
  MeshModel* m = add_bunny();
  const auto original = positions(*m);
  RichParameterList params = h.defaults(kOrientation, md);
  params.setValue("alphaMax", FloatValue(90.0f));
  EXPECT_FALSE(h.apply(kOrientation, md, params));
  EXPECT_TRUE(h.lastError().startsWith(kOrientation + ": ")) << h.lastError().toStdString();
  EXPECT_TRUE(h.lastError().contains("[0, 90)")) << h.lastError().toStdString();
  EXPECT_TRUE(h.logLines().join("\n").contains(h.lastError()));
  EXPECT_EQ(md.meshNumber(), 1u);
  EXPECT_EQ(positions(*m), original);
}
