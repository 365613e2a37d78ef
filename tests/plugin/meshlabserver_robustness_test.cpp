// The bad-input catalogue through the real meshlabserver (the private prefix, on a private Xvfb): a representative
// subset of the bad inputs (support/bad_inputs.h, meshlabserver = true) as PLY files and scripts
// for Support Slimming and Print Orientation,
// and hand-written scripts that are wrong in the ways a script can be. meshlabserver must never
// crash in our filter: a refusal ends the run with our reason in its output.
#include <gtest/gtest.h>

#include <QFile>
#include <QRegularExpression>
#include <QString>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/geometry/welded_view.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "filter_checks.h"
#include "harness.h"
#include "mesh_io/mesh_io.h"
#include "support/bad_inputs.h"
#include "support/shapes.h"
#include "support/source_paths.h"

using namespace slim;
using test::BadInput;
using test::mentions;
namespace fs = std::filesystem;

namespace {

// A scratch folder for one test, removed with everything in it at the end.
struct Scratch {
  const fs::path dir = fs::temp_directory_path() / ("slim-e2e-robust-" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  fs::path operator()(const std::string& name) const { return dir / name; }
};

QString example(const QString& file) {
  QFile in(QString::fromStdString(test::source_dir()) + "/examples/" + file);
  EXPECT_TRUE(in.open(QIODevice::ReadOnly));
  return QString::fromUtf8(in.readAll());
}

QString set_value(QString script, const QString& name, const QString& value) {
  return script.replace(QRegularExpression("(name=\"" + name + "\" value=\")[^\"]*\""), "\\1" + value + "\"");
}

QString number(double v) { return QString::number(v, 'g', 9); }  // "nan", "inf" as Qt reads them

// examples/support_slimming.mlx with the case's settings.
QString slimming_script(const BadInput& c) {
  const SlimmingOptions& o = c.options;
  QString s = example("support_slimming.mlx");
  s.replace(QRegularExpression(R"(x="[^"]*" y="[^"]*" z="[^"]*")"),
            QString(R"(x="%1" y="%2" z="%3")")
                .arg(number(o.print.direction.x()), number(o.print.direction.y()), number(o.print.direction.z())));
  s = set_value(s, "alphaMax", number(o.print.alpha_max_deg));
  s = set_value(s, "resolution", QString::number(o.resolution));
  s = set_value(s, "domain", o.domain == DomainKind::TetGen ? "1" : "0");
  s = set_value(s, "method", o.method == SlimmingMethod::Paper ? "1" : "0");
  s = set_value(s, "maxIterations", QString::number(o.steps.max_iterations));
  s = set_value(s, "maxDeviation", number(test::dialog_budget_mm(o.budget, c.surface)));
  s = set_value(s, "maxK", QString::number(o.steps.max_k));
  s = set_value(s, "allowStretch", o.hold_proportions ? "false" : "true");
  return s;
}

void write_text(const fs::path& path, const QString& text) {
  std::ofstream(path) << text.toStdString();
}

// Signs of a crash in meshlabserver's output.
bool crashed(const test::ServerRun& run) {
  return mentions(run.output, "Segmentation") || mentions(run.output, "Aborted") ||
         mentions(run.output, "terminate called") || mentions(run.output, "core dumped");
}

std::vector<BadInput> server_cases() {
  std::vector<BadInput> subset;
  for (BadInput& c : test::bad_inputs())
    if (c.meshlabserver) subset.push_back(std::move(c));
  return subset;
}

class BadInputServer : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputServer, SupportSlimmingSavesASaneLayerOrFailsWithItsReason) {
  const BadInput& c = GetParam();
  const Scratch scratch;
  const fs::path in = scratch(c.name + ".ply"), out = scratch(c.name + "_out.ply"), mlx = scratch(c.name + ".mlx");
  test::write_ascii_ply(in.string(), c.surface);
  write_text(mlx, slimming_script(c));
  fs::remove(out);
  const test::ServerRun run = test::run_meshlabserver("-i '" + in.string() + "' -o '" + out.string() +
                                                      "' -m fq fc vq sa -s '" + mlx.string() + "'");
  EXPECT_FALSE(crashed(run)) << run.output;
  if (!c.refusal.empty()) {
    EXPECT_EQ(run.exit_code, 255) << run.output;  // meshlabserver's exit(-1) after a failed script
    EXPECT_TRUE(mentions(run.output, "Problem with filter: Support Slimming")) << run.output;
    EXPECT_TRUE(mentions(run.output, c.refusal)) << c.name << ": " << run.output;
    EXPECT_TRUE(mentions(run.output, c.advice)) << c.name << ": " << run.output;
    EXPECT_FALSE(fs::exists(out)) << "a result was saved";
    return;
  }
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_FALSE(mentions(run.output, "Problem with filter")) << run.output;
  EXPECT_EQ(mentions(run.output, "inside out"), c.inside_out) << run.output;
  const Surface input = io::load_surface(in.string());
  io::FaceExtras saved;
  const Surface result = io::load_surface(out.string(), &saved);
  ASSERT_EQ(result.F.rows(), input.F.rows());
  ASSERT_EQ(saved.quality.size(), input.F.rows());
  ASSERT_TRUE(result.V.allFinite());
  // The saved face quality is the filter's measure: its negative part is the risky area left,
  // which must not exceed the input's.
  PrintSetup o;
  o.direction = c.options.print.direction;
  o.alpha_max_deg = c.options.print.alpha_max_deg;
  o.plate = PlateRule::within(0.0157572);  // as in the script
  const OverhangReport was = analyse_overhang(c.inside_out ? flipped(input) : input, o);
  const Eigen::VectorXd areas = face_areas(result);
  double risky = 0.0;
  for (Eigen::Index f = 0; f < areas.size(); ++f)
    if (saved.quality(f) < 0) risky += areas(f);
  EXPECT_LE(risky, was.risky_area + 1e-4 * was.total_area) << c.name;
  const double diag = (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm();
  const double ulps = 1e-6 * std::max(diag, input.V.cwiseAbs().maxCoeff());
  const Eigen::Vector3d d = c.options.print.direction.normalized();
  EXPECT_GE((result.V * d).minCoeff(), (input.V * d).minCoeff() - ulps) << c.name;
  EXPECT_LE((result.V - input.V).rowwise().norm().maxCoeff(), c.options.budget.share_percent().value_or(0.0) / 100.0 * diag + ulps);
}

TEST_P(BadInputServer, PrintOrientationSavesTheBestPoseOrFailsWithItsReason) {
  // The oracle is the core on the mesh as read back from the file meshlabserver reads.
  const BadInput& c = GetParam();
  const Scratch scratch;
  const fs::path in = scratch(c.name + ".ply"), out = scratch(c.name + "_oriented.ply"), mlx = scratch(c.name + ".mlx");
  test::write_ascii_ply(in.string(), c.surface);
  write_text(mlx, set_value(set_value(example("print_orientation.mlx"), "alphaMax", number(c.options.print.alpha_max_deg)),
                            "searchEffort", "0"));
  fs::remove(out);
  const test::ServerRun run = test::run_meshlabserver("-i '" + in.string() + "' -o '" + out.string() +
                                                      "' -m fq fc sa -s '" + mlx.string() + "'");
  EXPECT_FALSE(crashed(run)) << run.output;
  const Surface input = io::load_surface(in.string());
  std::string refusal;
  const OrientationResult expected = test::fast_orientation(input, c.options.print.alpha_max_deg, refusal);
  if (!refusal.empty()) {
    EXPECT_EQ(run.exit_code, 255) << run.output;
    EXPECT_TRUE(mentions(run.output, "Problem with filter: Print Orientation")) << run.output;
    EXPECT_TRUE(mentions(run.output, mentions(refusal, "no faces") ? std::string("no faces") : refusal))
        << c.name << ": " << refusal << "\n" << run.output;
    EXPECT_FALSE(fs::exists(out)) << "a result was saved";
    return;
  }
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_FALSE(mentions(run.output, "Problem with filter")) << run.output;
  const Surface result = io::load_surface(out.string());
  ASSERT_EQ(result.F, input.F);
  ASSERT_TRUE(result.V.allFinite());
  const double size = std::max(1.0, input.V.cwiseAbs().maxCoeff());
  const WeldedView view = weld_coincident(input);  // the filter turns the welded view; each copy follows
  const Points posed = view.positions_to_input(input.V, apply_orientation(view.surface, expected.rotation).V);
  EXPECT_LT((result.V - posed).cwiseAbs().maxCoeff(), 1e-5 * size) << c.name;
  EXPECT_NEAR(result.V.col(2).minCoeff(), 0.0, 1e-5 * size) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputServer, ::testing::ValuesIn(server_cases()),
                         [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

}  // namespace

TEST(MeshlabserverScripts, MalformedScriptsNeverCrashInOurFilter) {
  // What meshlabserver 2020.09 does with each, and what our filter adds when it is reached.
  struct Fault {
    const char* name;
    QString script;
    int exit_code;         // 255: exit(-1); 134: SIGABRT (an assert), as the shell reports it
    const char* expected;  // in the output
    bool reaches_filter;   // our filter runs (and must fail cleanly)
  };
  const QString good = example("support_slimming.mlx");
  const Fault faults[] = {
      // meshlabserver merges missing parameters in after asserting that none is missing: it aborts
      // before our filter is called. Its own behaviour; scripts must list every parameter.
      {"missing parameter", QString(good).remove(QRegularExpression(R"(\s*<Param[^>]*name="alphaMax"[^>]*/>)")), 134,
       "Assertion", false},
      // A value MeshLab cannot read drops the parameter: the same assert.
      {"unreadable value", set_value(good, "maxDeviation", "five"), 134, "Assertion", false},
      // Reaches our filter, whose parameter check refuses it (MeshLab's own getter would assert).
      {"wrong type", QString(good).replace(R"(type="RichFloat" name="alphaMax")", R"(type="RichInt" name="alphaMax")"), 255,
       "is a RichInt, but it must be a RichFloat", true},
      {"enum out of range", set_value(good, "domain", "5"), 255, "must be one of 0..1", true},
      {"unknown filter", QString(good).replace(R"(name="Support Slimming")", R"(name="Support Slimmming")"), 255,
       "filter Support Slimmming not found", false},
      {"more parameters than the filter has",
       QString(good).replace("</filter>", R"(<Param type="RichInt" name="extra" value="1"/></filter>)"), 255,
       "more than the filter Support Slimming requires", false},
      // Not XML at all: meshlabserver reports it as a missing file.
      {"not XML", "<FilterScript><filter name=", 255, "was not found", false},
  };
  const Scratch scratch;
  const fs::path in = scratch("t.ply");
  test::write_ascii_ply(in.string(), test::t_shape());
  for (const Fault& f : faults) {
    const fs::path mlx = scratch("fault.mlx"), out = scratch("fault_out.ply");
    write_text(mlx, f.script);
    fs::remove(out);
    const test::ServerRun run = test::run_meshlabserver("-i '" + in.string() + "' -o '" + out.string() + "' -s '" +
                                                        mlx.string() + "'");
    EXPECT_EQ(run.exit_code, f.exit_code) << f.name << ": " << run.output;
    EXPECT_TRUE(mentions(run.output, f.expected)) << f.name << ": " << run.output;
    EXPECT_FALSE(fs::exists(out)) << f.name;
    if (f.reaches_filter) {
      EXPECT_FALSE(crashed(run)) << f.name << ": " << run.output;
      EXPECT_TRUE(mentions(run.output, "Problem with filter: Support Slimming")) << f.name << ": " << run.output;
    }
  }
}

TEST(MeshlabserverScripts, AWrongTypeAbortsMeshLabsOwnFiltersWhichIsWhyOursChecksFirst) {
  // The control for "wrong type" above: one of MeshLab's own filters reads the value with its
  // typed getter, which asserts, and meshlabserver dies with SIGABRT.
  const Scratch scratch;
  const fs::path in = scratch("t.ply"), mlx = scratch("laplacian.mlx");
  test::write_ascii_ply(in.string(), test::t_shape());
  write_text(mlx, R"(<!DOCTYPE FilterScript><FilterScript><filter name="Laplacian Smooth">
    <Param type="RichFloat" value="3" name="stepSmoothNum"/><Param type="RichBool" value="true" name="Boundary"/>
    <Param type="RichBool" value="true" name="cotangentWeight"/><Param type="RichBool" value="false" name="Selected"/>
    </filter></FilterScript>)");
  const test::ServerRun run = test::run_meshlabserver("-i '" + in.string() + "' -s '" + mlx.string() + "'");
  EXPECT_EQ(run.exit_code, 134) << run.output;
  EXPECT_TRUE(mentions(run.output, "Value::getInt() const: Assertion")) << run.output;
}

TEST(MeshlabserverScripts, InsideOutMeshIsAnalysedTurnedOverAndSaidSo) {
  const Scratch scratch;
  const fs::path in = scratch("inside_out.ply"), out = scratch("inside_out_overhang.ply");
  test::write_ascii_ply(in.string(), flipped(test::t_shape()));
  const test::ServerRun run = test::run_meshlabserver("-i '" + in.string() + "' -o '" + out.string() +
                                                      "' -m fq -s '" + test::source_dir() + "/examples/overhang_analysis.mlx'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(mentions(run.output, "inside out")) << run.output;
  // The risky faces are the T's arm undersides, as if it were the right way out.
  EXPECT_TRUE(mentions(run.output, "risky area 400 mm^2")) << run.output;
}
