// support-slim --report: every figure of the summary as JSON, checked against the files the run
// wrote and the core's own measures of them (support model, volume, creases, distance).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "cli_run.h"
#include "core/geometry/shape_metrics.h"
#include "core/geometry/surface_distance.h"
#include "core/support_model/support_model.h"
#include "mesh_io/mesh_io.h"
#include "support/project_version.h"
#include "support/shapes.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

// The report's numeric keys (a flat object, one key per line, as the CLI writes it).
std::map<std::string, double> read_numbers(const fs::path& path, std::string& text) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  text = ss.str();
  std::map<std::string, double> numbers;
  const std::regex line("\"([a-z0-9_]+)\": (-?[0-9][0-9.e+-]*)[,\n]");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), line); it != std::sregex_iterator(); ++it)
    numbers[(*it)[1]] = std::stod((*it)[2]);
  return numbers;
}

}  // namespace

TEST(CliReport, FiguresAreThoseOfTheFilesWritten) {
  const fs::path dir = test::scratch();
  const fs::path out = dir / "bunny.ply", report = dir / "bunny.json";
  const test::CliRun r = test::run_cli("'" + test::sample_bunny_path() + "' -o '" + out.string() + "' --report '" +
                                       report.string() + "' --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text;
  const std::map<std::string, double> f = read_numbers(report, text);
  for (const char* key : {"support_estimate_before_mm3", "support_estimate_after_mm3", "support_slicer_phase_before_mm3",
                          "support_slicer_phase_after_mm3", "support_slicer_phase_change_pct", "volume_change_pct",
                          "crease_share_pct", "crease_p99_deg", "hausdorff_pct", "hausdorff_mm", "max_displacement_mm",
                          "budget_mm", "budget_pct", "risky_area_before_mm2", "risky_area_after_mm2", "iterations", "resolution"})
    EXPECT_EQ(f.count(key), 1u) << key << "\n" << text;
  EXPECT_NE(text.find("\"stop_reason\": \""), std::string::npos) << text;
  // The voxel resolution the result came from: one of the ladder's rungs (24, 32, 48 by default).
  EXPECT_TRUE(f.at("resolution") == 24 || f.at("resolution") == 32 || f.at("resolution") == 48) << f.at("resolution");

  const Surface in = test::sample_bunny(), slimmed = io::load_surface(out.string());
  const double diag = test::bbox_diagonal(in);
  // The support model's figures, of the input and of the file written (float coordinates in it).
  EXPECT_NEAR(f.at("support_estimate_before_mm3"), estimate_support(in).volume_mm3, 1e-9 * f.at("support_estimate_before_mm3"));
  EXPECT_NEAR(f.at("support_estimate_after_mm3"), estimate_support(slimmed).volume_mm3, 1e-3 * f.at("support_estimate_after_mm3"));
  EXPECT_LT(f.at("support_estimate_after_mm3"), f.at("support_estimate_before_mm3"));
  // And at the slicer's own grid phase (one phase, the part as placed): the prediction for these files.
  SupportModelOptions at_phase;
  at_phase.grid_phases = 1;
  EXPECT_NEAR(f.at("support_slicer_phase_before_mm3"), estimate_support(in, at_phase).volume_mm3, 1e-9 * f.at("support_estimate_before_mm3"));
  EXPECT_NEAR(f.at("support_slicer_phase_after_mm3"), estimate_support(slimmed, at_phase).volume_mm3,
              1e-3 * f.at("support_estimate_after_mm3"));
  EXPECT_NEAR(f.at("support_slicer_phase_change_pct"),
              100 * (f.at("support_slicer_phase_after_mm3") / f.at("support_slicer_phase_before_mm3") - 1), 1e-6);
  // The shape's cost.
  const ShapeChange shape = shape_change(in, slimmed);
  EXPECT_NEAR(f.at("volume_change_pct"), shape.volume_change_pct, 1e-3);
  EXPECT_NEAR(f.at("crease_share_pct"), shape.crease_share_pct, 0.05);
  EXPECT_NEAR(f.at("hausdorff_mm"), surface_distance(in, slimmed).hausdorff_mm, 1e-3);
  EXPECT_NEAR(f.at("hausdorff_pct"), 100 * f.at("hausdorff_mm") / diag, 1e-9);
  const double moved = (slimmed.V - in.V).rowwise().norm().maxCoeff();
  EXPECT_NEAR(f.at("max_displacement_mm"), moved, 1e-4);
  // The proportions, from the files: the extents of their boxes, the height along +Z, the mean
  // move, the faces turned over, and the best-fit affine map with its translation by QR.
  const Eigen::RowVector3d box_in = in.V.colwise().maxCoeff() - in.V.colwise().minCoeff();
  const Eigen::RowVector3d box_out = slimmed.V.colwise().maxCoeff() - slimmed.V.colwise().minCoeff();
  const char* extent_keys[3] = {"extent_change_x_pct", "extent_change_y_pct", "extent_change_z_pct"};
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_NEAR(f.at(extent_keys[axis]), 100 * (box_out(axis) / box_in(axis) - 1), 1e-3) << extent_keys[axis];
  EXPECT_EQ(f.at("height_change_pct"), f.at("extent_change_z_pct"));
  EXPECT_NEAR(f.at("mean_displacement_pct"), 100 * (slimmed.V - in.V).rowwise().norm().mean() / diag, 1e-4);
  long folded = 0;
  for (Eigen::Index i = 0; i < in.F.rows(); ++i) {
    auto cross = [&](const Points& V) {
      const Eigen::Vector3d a = V.row(in.F(i, 0)), b = V.row(in.F(i, 1)), c = V.row(in.F(i, 2));
      return Eigen::Vector3d((b - a).cross(c - a));
    };
    folded += cross(in.V).dot(cross(slimmed.V)) < 0;
  }
  EXPECT_EQ(f.at("folded_faces"), static_cast<double>(folded));
  Eigen::MatrixXd X(in.V.rows(), 4);
  X << in.V, Eigen::VectorXd::Ones(in.V.rows());
  const Eigen::MatrixXd fit = X.colPivHouseholderQr().solve(Eigen::MatrixXd(slimmed.V));  // 4 by 3: [A^T; t^T]
  const Eigen::Vector3d sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(Eigen::Matrix3d(fit.topRows(3))).singularValues();
  EXPECT_NEAR(f.at("affine_departure_pct"), 100 * (sigma.array() - 1).abs().maxCoeff(), 1e-3);
  // The budget, as given and as a length, and both distances inside it.
  EXPECT_DOUBLE_EQ(f.at("budget_pct"), 5.0);
  EXPECT_NEAR(f.at("budget_mm"), 0.05 * diag, 1e-9 * diag);
  EXPECT_LE(f.at("max_displacement_mm"), f.at("budget_mm") * (1 + 1e-9));
  EXPECT_LE(f.at("hausdorff_mm"), f.at("budget_mm") * (1 + 1e-6));
  // The summary says the same.
  for (const char* line : {"  support         ", "  shape           Hausdorff ", "  budget          "})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  EXPECT_EQ(f.at("open_edges"), 0.0);  // the bunny is closed: no note on holes
  EXPECT_EQ(r.out.find("the mesh is open"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

// An open mesh: the report counts the edges that border its holes, the summary says what slicers
// do with them, and the support estimate counts the slices a slicer loses (a box with a 5 mm window
// in its side: PrusaSlicer empties the slices through it and supports the box above them).
TEST(CliReport, AnOpenMeshIsNamedAndItsLostSlicesCounted) {
  const fs::path dir = test::scratch();
  const fs::path in = dir / "window_box.ply", out = dir / "slim.ply", report = dir / "slim.json";
  const Surface box = test::box_with_windows(5.0);
  io::save_surface(in.string(), box);
  const test::CliRun r = test::run_cli("'" + in.string() + "' -o '" + out.string() + "' --report '" + report.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text;
  const std::map<std::string, double> f = read_numbers(report, text);
  EXPECT_EQ(f.at("open_edges"), static_cast<double>(edge_topology(box).open_edges));
  EXPECT_GT(f.at("open_edges"), 0.0);
  EXPECT_NE(r.out.find("the mesh is open (" + std::to_string(edge_topology(box).open_edges) + " edges border holes)"),
            std::string::npos) << r.out;
  EXPECT_NEAR(f.at("support_estimate_before_mm3"), estimate_support(box).volume_mm3, 1e-6 * f.at("support_estimate_before_mm3"));
  EXPECT_GT(f.at("support_estimate_before_mm3"), 1000.0);
  fs::remove_all(dir);
}

// --max-creases: the file written creases no more than the limit (measured again on it; its float
// coordinates move the angles a little), below the default run's share, and still saves support
// (any saving: so tight a limit keeps only the first iterates, which save under the default 3%).
TEST(CliReport, TheCreaseLimitHoldsInTheFileWritten) {
  const fs::path dir = test::scratch();
  const Surface in = test::sample_bunny();
  double share[2];
  for (int limited = 0; limited < 2; ++limited) {
    const fs::path out = dir / "bunny.ply", report = dir / "bunny.json";
    const test::CliRun r = test::run_cli("'" + test::sample_bunny_path() + "' -o '" + out.string() + "' --report '" +
                                         report.string() + "' --quiet" + (limited ? " --max-creases 0.05 --min-saving 0" : ""));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::string text;
    const std::map<std::string, double> f = read_numbers(report, text);
    share[limited] = shape_change(in, io::load_surface(out.string())).crease_share_pct;
    EXPECT_LT(f.at("support_estimate_after_mm3"), f.at("support_estimate_before_mm3")) << limited;
  }
  EXPECT_LE(share[1], 0.05 + 0.02);
  EXPECT_GT(share[0], 0.05 + 0.02) << "the default run no longer tests the limit";
  fs::remove_all(dir);
}

// The resolution ladder (resolution_ladder.h) in the summary and the report: by default the
// bunny is slimmed at 24, 32 and 48 cells and the summary gives each rung's estimate, the report
// the rung kept; --one-resolution slims at --resolution alone, and that run is the ladder's own
// first rung (the same estimate, to the digits printed).
TEST(CliReport, TheResolutionLadderIsSaidAndOneResolutionTurnsItOff) {
  const fs::path dir = test::scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "' -o '" + (dir / "out.ply").string() + "' --report '";
  const test::CliRun ladder = test::run_cli(bunny + (dir / "ladder.json").string() + "' --verbose");
  ASSERT_EQ(ladder.exit_code, 0) << ladder.err;
  const std::smatch rungs = [&] {
    std::smatch m;
    // The summary folds long lines: any space may be a line break and an indent.
    const std::regex line(
        R"(  resolution\s+(\d+)\s+cells\s+along\s+the\s+longest\s+side;\s+the\s+least\s+support\s+of\s+24\s+\(([0-9.]+)\s+mm\^3\),)"
        R"(\s+32\s+\(([0-9.]+)\s+mm\^3\),\s+48\s+\(([0-9.]+)\s+mm\^3\))");
    EXPECT_TRUE(std::regex_search(ladder.out, m, line)) << ladder.out;
    return m;
  }();
  ASSERT_EQ(rungs.size(), 5u);
  std::string text;
  const std::map<std::string, double> f = read_numbers(dir / "ladder.json", text);
  EXPECT_EQ(f.at("resolution"), std::stod(rungs[1]));
  // The rung kept has the least estimate of the three, and it is the result's.
  const double least = std::min({std::stod(rungs[2]), std::stod(rungs[3]), std::stod(rungs[4])});
  EXPECT_NEAR(f.at("support_estimate_after_mm3"), least, 1e-5 * least);
  EXPECT_NEAR(std::stod(rungs[2 + (f.at("resolution") == 32) + 2 * (f.at("resolution") == 48)]), least, 1e-12 * least);

  const test::CliRun one = test::run_cli(bunny + (dir / "one.json").string() + "' --one-resolution --verbose");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("  resolution      24 cells along the longest side\n"), std::string::npos) << one.out;
  const std::map<std::string, double> g = read_numbers(dir / "one.json", text);
  EXPECT_EQ(g.at("resolution"), 24);
  EXPECT_NEAR(g.at("support_estimate_after_mm3"), std::stod(rungs[2]), 1e-5 * g.at("support_estimate_after_mm3"));
  EXPECT_LE(f.at("support_estimate_after_mm3"), g.at("support_estimate_after_mm3"));
  fs::remove_all(dir);
}

// By default the bunny keeps its proportions (the report's affine map within 1% of a rigid
// motion, the top risen at most 1% of the height); --allow-stretch lets the whole part move, and
// the report says it departs further from a rigid motion.
TEST(CliReport, AllowStretchLetsThePartStretch) {
  const fs::path dir = test::scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "' -o '" + (dir / "out.ply").string() + "' --quiet --report '";
  std::string text;
  ASSERT_EQ(test::run_cli(bunny + (dir / "held.json").string() + "'").exit_code, 0);
  ASSERT_EQ(test::run_cli(bunny + (dir / "free.json").string() + "' --allow-stretch").exit_code, 0);
  const std::map<std::string, double> held = read_numbers(dir / "held.json", text), free = read_numbers(dir / "free.json", text);
  EXPECT_LE(held.at("affine_departure_pct"), 1.0);
  EXPECT_LE(held.at("height_change_pct"), 1.0 + 1e-9);
  EXPECT_LE(held.at("mean_displacement_pct"), 1.5);
  EXPECT_EQ(held.at("folded_faces"), 0);
  EXPECT_GT(free.at("affine_departure_pct"), held.at("affine_departure_pct") + 0.5);
  fs::remove_all(dir);
}

TEST(CliReport, AnUnwritableReportExitsWithOneLine) {
  const fs::path dir = test::scratch();
  const test::CliRun r = test::run_cli("'" + test::sample_bunny_path() + "' -o '" + (dir / "b.ply").string() +
                                       "' --iterations 0 --report '" + (dir / "no/such/dir/r.json").string() + "' --quiet");
  EXPECT_EQ(r.exit_code, 2);  // bad usage: an output path that cannot be written
  EXPECT_NE(r.err.find("support-slim: cannot write the report"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "b.ply")) << "refused before the run: nothing written";
  fs::remove_all(dir);
}

// The report names the build that made it (the version CMakeLists.txt declares, as --version
// prints it) and the settings the run read.
TEST(CliReport, NamesTheVersionAndTheSettings) {
  const std::string version = test::project_version();
  ASSERT_FALSE(version.empty());
  const test::CliRun v = test::run_cli("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.out, "support-slim " + version + "\n");

  const fs::path dir = test::scratch();
  const std::string base = "'" + test::sample_bunny_path() + "' -o '" + (dir / "b.ply").string() + "' --iterations 0 --quiet --report '";
  ASSERT_EQ(test::run_cli(base + (dir / "a.json").string() + "' --angle 40 --dir 0,0,2 --max-creases 3 --allow-stretch --one-resolution").exit_code, 0);
  ASSERT_EQ(test::run_cli(base + (dir / "p.json").string() + "' --method paper --resolution 20").exit_code, 0);
  std::string a, p;
  const std::map<std::string, double> an = read_numbers(dir / "a.json", a), pn = read_numbers(dir / "p.json", p);
  for (const std::string& text : {a, p}) EXPECT_NE(text.find("\"version\": \"" + version + "\""), std::string::npos) << text;
  EXPECT_NE(a.find("\"method\": \"coherent\""), std::string::npos) << a;
  EXPECT_EQ(an.at("alpha_max_deg"), 40.0);
  EXPECT_NE(a.find("\"print_direction_given\": [0, 0, 2]"), std::string::npos) << a;
  EXPECT_EQ(an.at("max_creases_pct"), 3.0);
  EXPECT_EQ(an.at("max_displacement_pct"), 1.5);
  EXPECT_EQ(an.at("resolution_given"), 24.0);
  EXPECT_EQ(an.at("scale"), 1.0);
  EXPECT_NE(a.find("\"one_resolution\": true"), std::string::npos) << a;
  EXPECT_NE(a.find("\"allow_stretch\": true"), std::string::npos) << a;
  // The paper's method reads no limits and always lets the part stretch.
  EXPECT_NE(p.find("\"method\": \"paper\""), std::string::npos) << p;
  EXPECT_EQ(pn.at("resolution_given"), 20.0);
  EXPECT_EQ(pn.at("max_creases_pct"), 0.0);
  EXPECT_EQ(pn.at("min_saving_pct"), 0.0);
  EXPECT_NE(p.find("\"allow_stretch\": true"), std::string::npos) << p;
  fs::remove_all(dir);
}

// The summary leads with the verdict, the same figures as the report; the internals wait for
// --verbose; progress into a file (not a terminal) is a plain line per stage, never a '\r'.
TEST(CliReport, TheSummaryLeadsWithTheVerdict) {
  const fs::path dir = test::scratch();
  const std::string in = test::sample_bunny_path(), out = (dir / "b.ply").string();
  const test::CliRun r = test::run_cli("'" + in + "' -o '" + out + "' --one-resolution --report '" + (dir / "r.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text;
  const std::map<std::string, double> f = read_numbers(dir / "r.json", text);
  char verdict[400];
  std::snprintf(verdict, sizeof verdict, "support-slim: %s -> %s: support %.4g -> %.4g mm^3 (%+.1f%%, the support model's estimate)\n",
                in.c_str(), out.c_str(), f.at("support_estimate_before_mm3"), f.at("support_estimate_after_mm3"),
                f.at("support_change_pct"));
  EXPECT_EQ(r.out.rfind(verdict, 0), 0u) << verdict << r.out;
  EXPECT_NE(text.find("\"unchanged\": false"), std::string::npos) << text;
  EXPECT_NE(text.find("\"unchanged_reason\": \"\""), std::string::npos) << text;
  for (const char* internal : {"support proxy", "AE  ", "domain  ", "resolution  "})
    EXPECT_EQ(r.out.find(internal), std::string::npos) << internal << "\n" << r.out;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
  std::istringstream lines(r.err);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) EXPECT_EQ(line.rfind("[", 0), 0u) << line;
  EXPECT_NE(r.err.find("factoring the global step\n"), std::string::npos) << r.err;
  EXPECT_LE(count, 6) << r.err;  // the stages, not every iteration (the run made f.at("iterations_run"))
  EXPECT_GT(f.at("iterations_run"), 6.0);
  fs::remove_all(dir);
}
