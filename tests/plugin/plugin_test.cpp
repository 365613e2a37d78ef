// The built plugin, loaded with QPluginLoader the way MeshLab loads it, on meshes in a MeshDocument.
#include <gtest/gtest.h>

#include <QJsonObject>

#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "filter_checks.h"
#include "harness.h"
#include "support/project_version.h"
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

TEST(Plugin, LoadsWithItsMetadataAndFilters) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  const QJsonObject meta = h.metaData().value("MetaData").toObject();
  EXPECT_EQ(meta.value("name").toString(), "Support Slimming");
  EXPECT_EQ(meta.value("license").toString(), "GPL-3.0-or-later");
  EXPECT_EQ(meta.value("meshlabVersion").toString(), "2020.09");
  for (const QString& name : {kOverhang, kSlimming, kOrientation}) {
    ASSERT_NE(h.action(name), nullptr) << name.toStdString();
    EXPECT_NE(h.plugin()->getClass(h.action(name)), MeshFilterInterface::Generic);
  }
}

TEST(Plugin, OverhangAnalysisWritesQualityColourAndSelection) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  const Surface t = test::t_shape();
  MeshModel* m = test::add_layer(md, t, "T");
  RichParameterList params = h.defaults(kOverhang, md);
  ASSERT_TRUE(h.apply(kOverhang, md, params)) << h.lastError().toStdString();

  const OverhangReport expected = analyse_overhang(vcg_adapters::to_surface(m->cm));
  EXPECT_NEAR(expected.risky_area, test::t_shape_arm_underside_area(), 1e-3);
  test::expect_overhang_written(*m, expected);
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

TEST(Plugin, ExampleScriptsListEveryParameterAndRun) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  for (const auto& [file, filter] : {std::make_pair(QString("overhang_analysis.mlx"), kOverhang),
                                     std::make_pair(QString("support_slimming.mlx"), kSlimming),
                                     std::make_pair(QString("print_orientation.mlx"), kOrientation)}) {
    MeshDocument md;
    test::add_layer(md, test::t_shape(), "T");
    const RichParameterList defaults = h.defaults(filter, md);
    const RichParameterList scripted = test::example_script_params(file, filter);
    // meshlabserver asserts when a script omits a parameter: the examples must list them all.
    for (const RichParameter& p : defaults) EXPECT_TRUE(scripted.hasParameter(p.name())) << p.name().toStdString();
    EXPECT_EQ(scripted.size(), defaults.size()) << file.toStdString();
    ASSERT_TRUE(h.apply(filter, md, scripted)) << h.lastError().toStdString();
  }
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
  // A negative budget is refused, not taken as "no budget"; the document keeps its one layer.
  params = h.defaults(kSlimming, md);
  params.setValue("maxDeviation", AbsPercValue(-1.0f));
  EXPECT_FALSE(h.apply(kSlimming, md, params));
  EXPECT_TRUE(h.lastError().contains("deviation budget must be >= 0")) << h.lastError().toStdString();
  EXPECT_EQ(md.meshList.size(), 1);
}

TEST(Plugin, SupportSlimmingAddsASlimmedLayerAndLeavesTheInputAlone) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  const auto original = positions(*input);
  RichParameterList params = h.defaults(kSlimming, md);
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();

  ASSERT_EQ(md.meshList.size(), 2);
  test::expect_slimmed_layer(*input, *md.mm(), original, params.getAbsPerc("plateTolerance"), h.logLines());
  EXPECT_FALSE(h.logLines().join("\n").contains("the mesh is open")) << h.logLines().join("\n").toStdString();
  // The log's first line names the build that made the layer.
  ASSERT_FALSE(h.logLines().isEmpty());
  EXPECT_EQ(h.logLines().first().toStdString(), "Support Slimming: support-slimming " + test::project_version());
}

// The new layer is "<name>_slimmed", the input's file extension dropped, so that MeshLab 2020.09's
// layer list (which cuts a label at its last dot) does not show it as the input's own name.
TEST(Plugin, TheNewLayerIsNamedAfterTheInputWithoutItsExtension) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  for (const auto& [label, expected] : std::vector<std::pair<QString, QString>>{
           {"bunny.ply", "bunny_slimmed"}, {"Part 7.STL", "Part 7_slimmed"}, {"scan v1.2", "scan v1.2_slimmed"}, {"T", "T_slimmed"}}) {
    MeshDocument md;
    test::add_layer(md, test::t_shape(), label);
    RichParameterList params = h.defaults(kSlimming, md);
    params.setValue("maxIterations", IntValue(0));
    ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
    EXPECT_EQ(md.mm()->label().toStdString(), expected.toStdString());
  }
}

// A 2.5 mm part is most likely in another unit: the log says so and how to scale it.
TEST(Plugin, SupportSlimmingWarnsOfAPartTooSmallForMillimetres) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  test::add_layer(md, test::transformed(test::t_shape(), 0.05 * Eigen::Matrix3d::Identity()), "tiny T");
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("maxIterations", IntValue(0));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  const QString log = h.logLines().join("\n");
  EXPECT_TRUE(log.contains("Support Slimming: the part is 2.5 mm across at its largest, under 5 mm")) << log.toStdString();
  EXPECT_TRUE(log.contains("Transform: Scale, Normalize")) << log.toStdString();
}

// An open mesh (a box with a 5 mm window in its side) is slimmed like any other, and the log says
// what slicers do with its hole, which the support estimate counts.
TEST(Plugin, SupportSlimmingSaysWhatSlicersDoWithAnOpenMesh) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  const Surface box = test::box_with_windows(5.0);
  test::add_layer(md, box, "window box");
  ASSERT_TRUE(h.apply(kSlimming, md, h.defaults(kSlimming, md))) << h.lastError().toStdString();
  ASSERT_EQ(md.meshList.size(), 2);
  const QString log = h.logLines().join("\n");
  const std::string note = "the mesh is open (" + std::to_string(edge_topology(box).open_edges) + " edges border holes)";
  EXPECT_TRUE(log.contains(QString::fromStdString(note))) << log.toStdString();
}

TEST(Plugin, SupportSlimmingPaperMethodRuns) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("method", EnumValue(1));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  EXPECT_EQ(md.meshList.size(), 2);
}

TEST(Plugin, RigidFeaturesNeedASelection) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  test::add_layer(md, test::t_shape(), "T");
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("preserveSelection", BoolValue(true));
  EXPECT_FALSE(h.apply(kSlimming, md, params));
  EXPECT_TRUE(h.lastError().contains("no face is selected")) << h.lastError().toStdString();
  EXPECT_TRUE(h.logLines().join("\n").contains("no face is selected"));
  EXPECT_EQ(md.meshList.size(), 1);
}

TEST(Plugin, CancelLeavesNoHalfBuiltLayer) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  const auto original = positions(*input);
  const RichParameterList params = h.defaults(kSlimming, md);
  test::progress_reports = 0;
  EXPECT_FALSE(h.plugin()->applyFilter(h.action(kSlimming), md, params, test::cancel_at_second_report));
  EXPECT_TRUE(h.lastError().contains("cancelled")) << h.lastError().toStdString();
  EXPECT_EQ(md.meshList.size(), 1);
  EXPECT_EQ(md.mm(), input);
  EXPECT_EQ(positions(*input), original);
}

TEST(Plugin, SupportSlimmingRefusesBadSettingsWithoutAddingALayer) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  test::add_layer(md, test::t_shape(), "T");
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("resolution", IntValue(100000));  // the memory guard
  EXPECT_FALSE(h.apply(kSlimming, md, params));
  EXPECT_TRUE(h.lastError().contains("resolution")) << h.lastError().toStdString();
  EXPECT_EQ(md.meshList.size(), 1);
}

TEST(Plugin, PrintOrientationAddsTheBestPoseAsANewLayer) {
  // The printable mushroom upside down: the new layer "<label> oriented" holds it cap up, resting
  // on z = 0, where the core puts it; the input layer keeps its positions; the log lists the top
  // five poses and the proxy and risky area before and after.
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  const Surface upside_down = test::transformed(test::printable_mushroom(), test::axis_angle({1, 0, 0}, M_PI), {5, 5, 30});
  MeshModel* input = test::add_layer(md, upside_down, "mushroom");
  const auto original = positions(*input);
  RichParameterList params = h.defaults(kOrientation, md);
  EXPECT_EQ(params.getFloat("alphaMax"), 45.0f);
  EXPECT_EQ(params.getEnum("searchEffort"), 1);
  EXPECT_TRUE(params.getBool("applyResult"));
  ASSERT_TRUE(h.apply(kOrientation, md, params)) << h.lastError().toStdString();

  ASSERT_EQ(md.meshList.size(), 2);
  MeshModel* out = md.mm();
  test::expect_oriented_layer(*input, *out, original, OrientationOptions{}, h.logLines());
  const Surface got = vcg_adapters::to_surface(out->cm);
  EXPECT_NEAR(got.V.col(2).maxCoeff(), 20.0, 1e-4);  // cap up: the dome's apex on top
  for (const auto& f : out->cm.face) EXPECT_FALSE(f.IsS());  // nothing overhangs cap up
}

TEST(Plugin, PrintOrientationOnlyReportsWhenNotApplied) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::t_shape(), "T");
  RichParameterList params = h.defaults(kOrientation, md);
  params.setValue("applyResult", BoolValue(false));
  params.setValue("searchEffort", EnumValue(0));
  ASSERT_TRUE(h.apply(kOrientation, md, params)) << h.lastError().toStdString();
  EXPECT_EQ(md.meshList.size(), 1);
  EXPECT_FALSE(input->hasDataMask(MeshModel::MM_FACEQUALITY));
  EXPECT_TRUE(h.logLines().join("\n").contains("support proxy"));
  // Bad settings are refused with the core's reason, and nothing is added.
  params.setValue("applyResult", BoolValue(true));
  params.setValue("alphaMax", FloatValue(90.0f));
  EXPECT_FALSE(h.apply(kOrientation, md, params));
  EXPECT_TRUE(h.lastError().contains("[0, 90)")) << h.lastError().toStdString();
  EXPECT_EQ(md.meshList.size(), 1);
}

TEST(Plugin, SupportSlimmingCanOptimizeTheOrientationFirst) {
  // The bunny: turned into its best pose first, then slimmed there. The new layer is the core's
  // orientation followed by its slimming; vertex quality (the displacement) is measured from the
  // oriented part, so it is the deformation alone.
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  const auto original = positions(*input);
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("optimizeOrientation", BoolValue(true));
  params.setValue("maxIterations", IntValue(4));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  ASSERT_EQ(md.meshList.size(), 2);
  EXPECT_EQ(positions(*input), original);

  const Surface seen = vcg_adapters::to_surface(input->cm);
  OrientationOptions oo;
  oo.plate = PlateRule::within(params.getAbsPerc("plateTolerance"));
  const Surface oriented = apply_orientation(seen, optimize_orientation(seen, oo).rotation);
  const Surface got = vcg_adapters::to_surface(md.mm()->cm);
  const Eigen::VectorXd moved = (got.V - oriented.V).rowwise().norm();
  EXPECT_GT(moved.maxCoeff(), 0.0);
  EXPECT_LT(moved.maxCoeff(), 0.06 * (seen.V.colwise().maxCoeff() - seen.V.colwise().minCoeff()).norm());
  for (int v = 0; v < md.mm()->cm.vn; ++v) EXPECT_NEAR(md.mm()->cm.vert[static_cast<size_t>(v)].Q(), moved(v), 1e-4);
  const QString log = h.logLines().join("\n");
  EXPECT_TRUE(log.contains("Support Slimming: print direction (")) << log.toStdString();
  EXPECT_TRUE(log.contains("the deformation alone")) << log.toStdString();
}

TEST(Plugin, ResultLayersCarryTheMatrixOfTheirFrame) {
  // The filters work on a layer's own coordinates. A slimmed part stays in the input's frame and
  // keeps its transformation matrix, so it shows where the input shows; a part in its print pose
  // (+Z up on z = 0) is in the plate's frame and gets the identity.
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = test::add_layer(md, test::load_mesh(test::sample_bunny_path()), "bunny");
  Matrix44m moved;
  moved.SetRotateDeg(30, vcg::Point3<Scalarm>(1, 0, 0));
  moved.ElementAt(0, 3) = 7;
  input->cm.Tr = moved;

  ASSERT_TRUE(h.apply(kOrientation, md, h.defaults(kOrientation, md))) << h.lastError().toStdString();
  EXPECT_EQ(md.mm()->label(), "bunny_oriented");
  EXPECT_TRUE(md.mm()->cm.Tr == Matrix44m::Identity());

  md.setCurrentMesh(input->id());
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("maxIterations", IntValue(2));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  EXPECT_EQ(md.mm()->label(), "bunny_slimmed");
  EXPECT_TRUE(md.mm()->cm.Tr == moved);

  md.setCurrentMesh(input->id());
  params.setValue("optimizeOrientation", BoolValue(true));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  EXPECT_TRUE(md.mm()->cm.Tr == Matrix44m::Identity());
  EXPECT_TRUE(input->cm.Tr == moved);  // the input layer keeps its own
}
