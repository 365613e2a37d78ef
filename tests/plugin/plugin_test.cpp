// The built plugin, loaded with QPluginLoader the way MeshLab loads it, on meshes in a MeshDocument.
#include <gtest/gtest.h>

#include <QApplication>
#include <QJsonObject>

#include <common/filterscript.h>

#include "core/overhang.h"
#include "harness.h"
#include "support/shapes.h"
#include "vcg_adapters/surface_adapter.h"

using namespace slim;
using slim::test::PluginHarness;

namespace {
const QString kOverhang = "Overhang Analysis";

// Reads an example .mlx the way meshlabserver does and returns the parameters of `filter`.
RichParameterList script_params(const QString& file, const QString& filter) {
  FilterScript script;
  EXPECT_TRUE(script.open(QString(SLIM_SOURCE_DIR) + "/examples/" + file)) << file.toStdString();
  for (const auto& entry : script)
    if (entry.filterName() == filter) return entry.second;
  ADD_FAILURE() << filter.toStdString() << " not in " << file.toStdString();
  return {};
}
}  // namespace

TEST(Plugin, LoadsWithItsMetadataAndFilters) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  const QJsonObject meta = h.metaData().value("MetaData").toObject();
  EXPECT_EQ(meta.value("name").toString(), "Support Slimming");
  EXPECT_EQ(meta.value("license").toString(), "GPL-3.0-or-later");
  EXPECT_EQ(meta.value("meshlabVersion").toString(), "2020.09");
  ASSERT_NE(h.action(kOverhang), nullptr);
  EXPECT_NE(h.plugin()->getClass(h.action(kOverhang)), MeshFilterInterface::Generic);
}

TEST(Plugin, OverhangAnalysisWritesQualityColourAndSelection) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  const Surface t = test::t_shape();
  MeshModel* m = test::add_layer(md, t, "T");
  RichParameterList params = h.defaults(kOverhang, md);
  ASSERT_TRUE(h.apply(kOverhang, md, params)) << h.lastError().toStdString();

  const OverhangReport expected = analyse_overhang(vcgx::to_surface(m->cm));
  EXPECT_NEAR(expected.risky_area, test::t_shape_arm_underside_area(), 1e-3);
  ASSERT_TRUE(m->hasDataMask(MeshModel::MM_FACEQUALITY));
  ASSERT_TRUE(m->hasDataMask(MeshModel::MM_FACECOLOR));
  int selected = 0;
  for (int f = 0; f < m->cm.fn; ++f) {
    const CFaceO& face = m->cm.face[static_cast<size_t>(f)];
    EXPECT_NEAR(face.cQ(), expected.quality(f), 1e-6);
    EXPECT_EQ(face.IsS(), expected.risky[static_cast<size_t>(f)]);
    selected += face.IsS();
    // Risky faces sit on the red half of the ramp, safe ones on the blue half.
    if (expected.risky[static_cast<size_t>(f)]) EXPECT_GT(face.cC()[0], face.cC()[2]);
    else EXPECT_GE(face.cC()[2], face.cC()[0]);
  }
  EXPECT_EQ(selected, expected.risky_count);
  EXPECT_TRUE(h.logLines().join("\n").contains("risky area")) << h.logLines().join("\n").toStdString();
}

TEST(Plugin, OverhangAnalysisLeavesSelectionAloneWhenAsked) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* m = test::add_layer(md, test::t_shape(), "T");
  m->cm.face[0].SetS();  // a user selection that must survive
  RichParameterList params = h.defaults(kOverhang, md);
  params.setValue("selectRisky", BoolValue(false));
  ASSERT_TRUE(h.apply(kOverhang, md, params));
  EXPECT_TRUE(m->cm.face[0].IsS());
  for (int f = 1; f < m->cm.fn; ++f) EXPECT_FALSE(m->cm.face[static_cast<size_t>(f)].IsS());
}

TEST(Plugin, ExampleScriptListsEveryParameterAndRuns) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  test::add_layer(md, test::box({0, 0, 0}, {10, 10, 10}), "cube");
  const RichParameterList defaults = h.defaults(kOverhang, md);
  const RichParameterList scripted = script_params("overhang_analysis.mlx", kOverhang);
  // meshlabserver asserts when a script omits a parameter: the example must list them all.
  for (const RichParameter& p : defaults) EXPECT_TRUE(scripted.hasParameter(p.name())) << p.name().toStdString();
  EXPECT_EQ(scripted.size(), defaults.size());
  ASSERT_TRUE(h.apply(kOverhang, md, scripted)) << h.lastError().toStdString();
}

TEST(Plugin, EmptyMeshFailsWithAClearMessageInTheLog) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* m = md.addNewMesh("", "empty", true);
  vcg::tri::Allocator<CMeshO>::AddVertices(m->cm, 3);  // a point cloud: vertices, no faces
  const RichParameterList params = h.defaults(kOverhang, md);
  EXPECT_FALSE(h.apply(kOverhang, md, params));
  EXPECT_TRUE(h.lastError().contains("no faces")) << h.lastError().toStdString();
  EXPECT_TRUE(h.logLines().join("\n").contains("no faces"));
  EXPECT_EQ(m->cm.vn, 3);
}

TEST(Plugin, BadParametersFailWithoutTouchingTheLayer) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* m = test::add_layer(md, test::t_shape(), "T");
  RichParameterList params = h.defaults(kOverhang, md);
  params.setValue("alphaMax", FloatValue(95.0f));
  EXPECT_FALSE(h.apply(kOverhang, md, params));
  EXPECT_TRUE(h.lastError().contains("[0, 90)")) << h.lastError().toStdString();
  EXPECT_FALSE(m->hasDataMask(MeshModel::MM_FACEQUALITY));
  params = h.defaults(kOverhang, md);
  params.setValue("printDirection", Point3fValue(vcg::Point3f(0, 0, 0)));
  EXPECT_FALSE(h.apply(kOverhang, md, params));
  EXPECT_TRUE(h.lastError().contains("print direction")) << h.lastError().toStdString();
}

int main(int argc, char** argv) {
  qputenv("QT_QPA_PLATFORM", qgetenv("QT_QPA_PLATFORM").isEmpty() ? "offscreen" : qgetenv("QT_QPA_PLATFORM"));
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
