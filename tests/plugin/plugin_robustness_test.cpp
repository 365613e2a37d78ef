// The bad-input catalogue through the plugin as MeshLab runs it: every case
// (support/bad_inputs.h) through the three filters on a MeshDocument. A refusal must leave the
// document exactly as it was (no new layer, the input layer's data untouched) with the reason in
// the error message and the log; a success must give a sane layer. Then hand-written .mlx
// parameter lists that are wrong in the ways a script can be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

#include <QFile>
#include <QRegularExpression>
#include <QTemporaryDir>

#include <common/filterscript.h>

#include "core/geometry/welded_view.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "filter_checks.h"
#include "harness.h"
#include "support/bad_inputs.h"
#include "support/shapes.h"
#include "support/source_paths.h"
#include "vcg_adapters/surface_adapter.h"

using namespace slim;
using test::BadInput;
using test::mentions;
using test::PluginHarness;

namespace {
const QString kOverhang = "Overhang Analysis";
const QString kSlimming = "Support Slimming";
const QString kOrientation = "Print Orientation";

// Everything of a layer a failed filter must leave alone, compared bit for bit (NaN too).
struct LayerSnapshot {
  std::vector<vcg::Point3f> positions;
  std::vector<bool> selected;
  int vn = 0, fn = 0, mask = 0;
  explicit LayerSnapshot(const MeshModel& m) : vn(m.cm.vn), fn(m.cm.fn), mask(m.dataMask()) {
    for (const auto& v : m.cm.vert) positions.push_back(v.cP());
    for (const auto& f : m.cm.face) selected.push_back(f.IsS());
  }
  bool operator==(const LayerSnapshot& o) const {
    return vn == o.vn && fn == o.fn && mask == o.mask && selected == o.selected && positions.size() == o.positions.size() &&
           (positions.empty() || std::memcmp(positions.data(), o.positions.data(), positions.size() * sizeof(vcg::Point3f)) == 0);
  }
};

MeshModel* add_case_layer(MeshDocument& md, const BadInput& c) {
  MeshModel* m = test::add_layer(md, c.surface, QString::fromStdString(c.name));
  for (size_t f = 0; f < c.options.rigid_features.size(); ++f)
    if (c.options.rigid_features[f]) m->cm.face[f].SetS();
  return m;
}

// The dialog's values for this case.
RichParameterList slimming_params(PluginHarness& h, MeshDocument& md, const BadInput& c) {
  RichParameterList p = h.defaults(kSlimming, md);
  const SlimmingOptions& o = c.options;
  p.setValue("printDirection", Point3fValue(vcg::Point3f(float(o.print.direction.x()), float(o.print.direction.y()),
                                                         float(o.print.direction.z()))));
  p.setValue("alphaMax", FloatValue(float(o.print.alpha_max_deg)));
  p.setValue("resolution", IntValue(o.resolution));
  p.setValue("domain", EnumValue(o.domain == DomainKind::TetGen ? 1 : 0));
  p.setValue("method", EnumValue(o.method == SlimmingMethod::Paper ? 1 : 0));
  p.setValue("maxIterations", IntValue(o.steps.max_iterations));
  p.setValue("maxDeviation", AbsPercValue(float(test::dialog_budget_mm(o.budget, c.surface))));
  p.setValue("maxK", IntValue(o.steps.max_k));
  p.setValue("allowStretch", BoolValue(!o.hold_proportions));
  p.setValue("preserveSelection", BoolValue(c.preserve_selection));
  return p;
}

// The layer as the core sees it, and its overhangs (turned over when inside out).
OverhangReport measure(const MeshModel& m, const BadInput& c, double plate_tolerance) {
  const Surface s = vcg_adapters::to_surface(m.cm);
  PrintSetup o;
  o.direction = c.options.print.direction;
  o.alpha_max_deg = c.options.print.alpha_max_deg;
  o.plate = PlateRule::within(plate_tolerance);
  return analyse_overhang(c.inside_out ? flipped(s) : s, o);
}

// One filter run and what the user sees of it: success, the error message and the whole log.
struct Outcome {
  bool ok = false;
  std::string error, log;
};
Outcome run_filter(PluginHarness& h, const QString& filter, MeshDocument& md, const RichParameterList& params) {
  Outcome o;
  o.ok = h.apply(filter, md, params);
  o.error = h.lastError().toStdString();
  o.log = h.logLines().join("\n").toStdString();
  return o;
}

class BadInputPlugin : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputPlugin, SupportSlimmingAddsASaneLayerOrRefusesLeavingTheDocumentAlone) {
  const BadInput& c = GetParam();
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  MeshDocument md;
  MeshModel* input = add_case_layer(md, c);
  const LayerSnapshot before(*input);
  const RichParameterList params = slimming_params(h, md, c);
  const auto [ok, error, log] = run_filter(h, kSlimming, md, params);
  EXPECT_TRUE(LayerSnapshot(*input) == before) << c.name << ": the input layer changed";

  const std::string refusal = c.plugin_refusal.empty() ? c.refusal : c.plugin_refusal;
  if (!refusal.empty()) {
    ASSERT_FALSE(ok) << c.name << " was accepted";
    EXPECT_EQ(error.rfind("Support Slimming: ", 0), 0u) << error;
    EXPECT_TRUE(mentions(error, refusal)) << c.name << ": " << error;
    if (c.plugin_refusal.empty()) {
      EXPECT_TRUE(mentions(error, c.advice)) << c.name << ": " << error;
    }
    EXPECT_NE(log.find(error), std::string::npos) << "the reason is not in the log: " << log;
    EXPECT_EQ(md.meshList.size(), 1) << c.name << ": a layer was left behind";
    EXPECT_EQ(md.mm(), input);
    return;
  }
  ASSERT_TRUE(ok) << c.name << ": " << error;
  ASSERT_EQ(md.meshList.size(), 2);
  const MeshModel* out = md.mm();
  ASSERT_NE(out, input);
  ASSERT_EQ(out->cm.vn, input->cm.vn);
  ASSERT_EQ(out->cm.fn, input->cm.fn);
  for (const auto& v : out->cm.vert) ASSERT_TRUE(std::isfinite(v.cP()[0] + v.cP()[1] + v.cP()[2])) << c.name;
  EXPECT_TRUE(out->hasDataMask(MeshModel::MM_FACEQUALITY) && out->hasDataMask(MeshModel::MM_VERTQUALITY));

  // Sane statistics, measured on the layers (float positions: tolerances of a few float ulps).
  const Surface in_s = vcg_adapters::to_surface(input->cm), out_s = vcg_adapters::to_surface(out->cm);
  const double diag = (in_s.V.colwise().maxCoeff() - in_s.V.colwise().minCoeff()).norm();
  const double ulps = 1e-6 * std::max(diag, in_s.V.cwiseAbs().maxCoeff());
  const double tolerance = params.getAbsPerc("plateTolerance");
  const OverhangReport was = measure(*input, c, tolerance), now = measure(*out, c, tolerance);
  EXPECT_LE(now.risky_area, was.risky_area + 1e-6 * was.total_area) << c.name;
  const Eigen::Vector3d d = c.options.print.direction.normalized();
  EXPECT_GE((out_s.V * d).minCoeff(), (in_s.V * d).minCoeff() - ulps) << c.name << ": below the plate";
  if (c.options.budget.share_percent().value_or(0.0) > 0) {
    EXPECT_LE((out_s.V - in_s.V).rowwise().norm().maxCoeff(), c.options.budget.share_percent().value_or(0.0) / 100.0 * diag + ulps) << c.name;
  }
  for (int f = 0; f < out->cm.fn; ++f) {
    // The core measured double positions; the layer holds them as floats.
    EXPECT_NEAR(out->cm.face[static_cast<size_t>(f)].cQ(), now.quality(f), 5e-3) << c.name << " face " << f;
  }
  EXPECT_TRUE(mentions(log, "risky area")) << log;
  EXPECT_EQ(mentions(log, "inside out"), c.inside_out) << log;
}

TEST_P(BadInputPlugin, OverhangAnalysisColoursTheLayerOrRefusesLeavingItAlone) {
  const BadInput& c = GetParam();
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* m = add_case_layer(md, c);
  const LayerSnapshot before(*m);
  RichParameterList params = h.defaults(kOverhang, md);
  const RichParameterList slimming = slimming_params(h, md, c);
  for (const char* name : {"printDirection", "alphaMax"})
    params.setValue(name, slimming.getParameterByName(name).value());
  const auto [ok, error, log] = run_filter(h, kOverhang, md, params);
  if (!c.analysis_refusal.empty()) {
    ASSERT_FALSE(ok) << c.name << " was analysed";
    EXPECT_TRUE(mentions(error, c.analysis_refusal)) << c.name << ": " << error;
    EXPECT_NE(log.find(error), std::string::npos) << log;
    EXPECT_TRUE(LayerSnapshot(*m) == before) << c.name << ": the layer changed";
    return;
  }
  ASSERT_TRUE(ok) << c.name << ": " << error;
  ASSERT_TRUE(m->hasDataMask(MeshModel::MM_FACEQUALITY));
  const OverhangReport expected = measure(*m, c, params.getAbsPerc("plateTolerance"));
  for (int f = 0; f < m->cm.fn; ++f) {
    EXPECT_NEAR(m->cm.face[static_cast<size_t>(f)].cQ(), expected.quality(f), 1e-4) << c.name << " face " << f;
    EXPECT_EQ(m->cm.face[static_cast<size_t>(f)].IsS(), expected.risky[static_cast<size_t>(f)]) << c.name;
  }
  EXPECT_EQ(mentions(log, "inside out"), c.inside_out) << log;
  EXPECT_EQ(mentions(log, "not consistently oriented"), edge_topology(c.surface).flipped_edges > 0) << log;
}

TEST_P(BadInputPlugin, PrintOrientationAddsTheBestPoseOrRefusesLeavingTheDocumentAlone) {
  // The oracle is the core on the layer as the filter reads it: where the core refuses, the filter
  // refuses with the core's reason and leaves the document as it was; otherwise the new layer is
  // the core's best pose, finite and resting on z = 0.
  const BadInput& c = GetParam();
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  MeshModel* input = add_case_layer(md, c);
  const LayerSnapshot before(*input);
  RichParameterList params = h.defaults(kOrientation, md);
  params.setValue("alphaMax", FloatValue(float(c.options.print.alpha_max_deg)));
  params.setValue("searchEffort", EnumValue(0));
  const Surface seen = vcg_adapters::to_surface(input->cm);
  std::string core_refusal;
  const OrientationResult expected = test::fast_orientation(seen, params.getFloat("alphaMax"), core_refusal);
  const auto [ok, error, log] = run_filter(h, kOrientation, md, params);
  EXPECT_TRUE(LayerSnapshot(*input) == before) << c.name << ": the input layer changed";
  if (!core_refusal.empty()) {
    ASSERT_FALSE(ok) << c.name << " was accepted";
    // A layer with no faces is refused before the core is asked, in the plugin's own words.
    if (mentions(core_refusal, "no faces")) {
      EXPECT_EQ(error.rfind("Print Orientation: ", 0), 0u) << error;
      EXPECT_TRUE(mentions(error, "no faces")) << error;
    } else {
      EXPECT_EQ(error, "Print Orientation: " + core_refusal);
    }
    EXPECT_NE(log.find(error), std::string::npos) << "the reason is not in the log: " << log;
    EXPECT_EQ(md.meshList.size(), 1) << c.name << ": a layer was left behind";
    EXPECT_EQ(md.mm(), input);
    return;
  }
  ASSERT_TRUE(ok) << c.name << ": " << error;
  ASSERT_EQ(md.meshList.size(), 2);
  const Surface got = vcg_adapters::to_surface(md.mm()->cm);
  ASSERT_EQ(got.F, seen.F);
  ASSERT_TRUE(got.V.allFinite()) << c.name;
  // The filter turns the welded view (core/geometry/welded_view.h) about its centroid; each copy follows.
  const WeldedView view = weld_coincident(seen);
  const Surface posed{view.positions_to_input(seen.V, apply_orientation(view.surface, expected.rotation).V), seen.F};
  const double size = std::max(1.0, seen.V.cwiseAbs().maxCoeff());
  EXPECT_LT((got.V - posed.V).cwiseAbs().maxCoeff(), 1e-5 * size) << c.name;
  EXPECT_NEAR(got.V.col(2).minCoeff(), 0.0, 1e-5 * size) << c.name;
  EXPECT_TRUE(mentions(log, "support proxy")) << log;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputPlugin, ::testing::ValuesIn(test::bad_inputs()),
                         [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

// The parameters of a hand-written script: the example with `edit` applied to its text.
RichParameterList script_params(const QString& example, const QString& filter,
                                const std::function<QString(QString)>& edit) {
  QFile in(QString::fromStdString(test::source_dir()) + "/examples/" + example);
  EXPECT_TRUE(in.open(QIODevice::ReadOnly));
  QTemporaryDir dir;
  const QString path = dir.filePath("edited.mlx");
  QFile out(path);
  EXPECT_TRUE(out.open(QIODevice::WriteOnly));
  out.write(edit(QString::fromUtf8(in.readAll())).toUtf8());
  out.close();
  FilterScript script;
  EXPECT_TRUE(script.open(path));
  for (const auto& entry : script)
    if (entry.filterName() == filter) return entry.second;
  ADD_FAILURE() << "no " << filter.toStdString() << " in the edited script";
  return {};
}

struct ScriptFault {
  const char* name;
  QString (*edit)(QString);
  const char* problem;  // what the filter's error must say
};

const ScriptFault kScriptFaults[] = {
    {"missing parameter", [](QString s) { return s.remove(QRegularExpression(R"(\s*<Param[^>]*name="alphaMax"[^>]*/>)")); },
     "'alphaMax' (Self-supporting angle (deg)) is missing"},
    {"unreadable value (dropped by MeshLab)",
     [](QString s) { return s.replace(R"(name="maxDeviation" value="0.7879")", R"(name="maxDeviation" value="five")"); },
     "'maxDeviation' (Deviation budget) is missing"},
    {"wrong type", [](QString s) { return s.replace(R"(type="RichFloat" name="alphaMax")", R"(type="RichInt" name="alphaMax")"); },
     "is a RichInt, but it must be a RichFloat"},
    {"absolute value given as a plain float",
     [](QString s) {
       return s.replace(R"(type="RichAbsPerc" name="plateTolerance" value="0.0157572" min="0" max="15.7572")",
                        R"(type="RichFloat" name="plateTolerance" value="0.01")");
     },
     "is a RichFloat, but it must be a RichAbsPerc"},
    {"enum out of range",
     [](QString s) { return s.replace(R"(name="domain" value="0")", R"(name="domain" value="5")"); },
     "must be one of 0..1 (Voxel, TetGen)"},
    {"NaN angle", [](QString s) { return s.replace(R"(name="alphaMax" value="45")", R"(name="alphaMax" value="nan")"); },
     "[0, 90)"},
    {"infinite print direction", [](QString s) { return s.replace(R"(z="1")", R"(z="inf")"); }, "print direction"},
};

}  // namespace

TEST(PluginScripts, MalformedParameterListsFailWithTheirReasonAndLeaveTheDocumentAlone) {
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  for (const ScriptFault& fault : kScriptFaults) {
    MeshDocument md;
    MeshModel* m = test::add_layer(md, test::t_shape(), "T");
    const LayerSnapshot before(*m);
    const RichParameterList params = script_params("support_slimming.mlx", kSlimming, fault.edit);
    EXPECT_FALSE(h.apply(kSlimming, md, params)) << fault.name;
    EXPECT_TRUE(mentions(h.lastError().toStdString(), fault.problem)) << fault.name << ": " << h.lastError().toStdString();
    EXPECT_EQ(md.meshList.size(), 1) << fault.name;
    EXPECT_TRUE(LayerSnapshot(*m) == before) << fault.name;
  }
}

TEST(PluginLayers, DeletedButNotCompactedElementsAreSkipped) {
  // After "Delete Selected Faces" MeshLab keeps the deleted elements in its containers, flagged:
  // both filters must see only the live ones and write their results back in the same order.
  PluginHarness h;
  ASSERT_TRUE(h.ok());
  MeshDocument md;
  Surface t = test::arch();
  t.V.conservativeResize(t.V.rows() + 1, 3);
  t.V.bottomRows(1) << 0, 0, 50;  // a stray vertex, deleted below
  MeshModel* m = test::add_layer(md, t, "arch");
  vcg::tri::Allocator<CMeshO>::DeleteFace(m->cm, m->cm.face[3]);
  vcg::tri::Allocator<CMeshO>::DeleteVertex(m->cm, m->cm.vert.back());
  const Surface live = vcg_adapters::to_surface(m->cm);
  ASSERT_EQ(live.F.rows(), t.F.rows() - 1);
  ASSERT_EQ(live.V.rows(), t.V.rows() - 1);

  ASSERT_TRUE(h.apply(kOverhang, md, h.defaults(kOverhang, md))) << h.lastError().toStdString();
  const OverhangReport expected = analyse_overhang(live, PrintSetup{Eigen::Vector3d::UnitZ(), 45.0,
      PlateRule::within(h.defaults(kOverhang, md).getAbsPerc("plateTolerance"))});
  Eigen::Index f = 0;
  for (const auto& face : m->cm.face) {
    if (face.IsD()) continue;
    EXPECT_NEAR(face.cQ(), expected.quality(f++), 1e-4);
  }

  // The paper's method, which chooses by the shadow volume: on this coarse arch the default method
  // finds no iterate that the support model says needs less support, and hands the input back.
  RichParameterList params = h.defaults(kSlimming, md);
  params.setValue("method", EnumValue(1));
  ASSERT_TRUE(h.apply(kSlimming, md, params)) << h.lastError().toStdString();
  const MeshModel* out = md.mm();
  ASSERT_NE(out, m);
  EXPECT_EQ(out->cm.fn, m->cm.fn);
  EXPECT_EQ(out->cm.vn, m->cm.vn);
  EXPECT_LT(analyse_overhang(vcg_adapters::to_surface(out->cm)).risky_area, analyse_overhang(live).risky_area);
}
