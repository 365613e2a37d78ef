// End to end: the real meshlabserver (a copy in the private prefix, so it loads this build's
// plugin) runs the shipped example scripts on the sample bunny on a private Xvfb.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <regex>

#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "harness.h"
#include "mesh_io/mesh_io.h"
#include "support/shapes.h"
#include "support/source_paths.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("slim-e2e-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}
}  // namespace

TEST(Meshlabserver, OverhangAnalysisScriptOnTheBunny) {
  const std::string in = test::sample_bunny_path();
  ASSERT_TRUE(fs::exists(in)) << "run scripts/setup.sh first";
  const fs::path out = scratch("bunny_overhang.ply");
  const test::ServerRun run = test::run_meshlabserver(
      "-i '" + in + "' -o '" + out.string() + "' -m fq fc sa -s '" + test::source_dir() + "/examples/overhang_analysis.mlx'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_EQ(run.output.find("Problem with filter"), std::string::npos) << run.output;

  // The log's risky area is the core's figure for the same mesh and the script's options.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex(R"((\d+) risky faces of (\d+); risky area ([0-9.eE+-]+) mm\^2)")))
      << run.output;
  const Surface bunny = test::load_mesh(in);
  PrintSetup o;
  o.plate = PlateRule::within(0.0157572);  // as in the example script (the default for the bunny)
  const OverhangReport core = analyse_overhang(bunny, o);
  EXPECT_NEAR(std::stod(m[3]), core.risky_area, 1e-4 * core.risky_area);
  EXPECT_NEAR(std::stoi(m[1]), core.risky_count, 2);  // float vs double at the threshold
  EXPECT_GT(core.risky_count, 0);

  // The saved PLY carries face quality (n·d + tau, negative = risky) and colour.
  io::FaceExtras saved;
  const Surface back = io::load_surface(out.string(), &saved);
  ASSERT_EQ(back.F.rows(), bunny.F.rows());
  ASSERT_EQ(saved.quality.size(), bunny.F.rows());
  EXPECT_LT((saved.quality - core.quality).cwiseAbs().maxCoeff(), 1e-4);
  std::ifstream header(out);
  std::string text((std::istreambuf_iterator<char>(header)), {});
  const std::string head = text.substr(0, text.find("end_header"));
  const std::string face_part = head.substr(head.find("element face"));
  EXPECT_NE(face_part.find("property uchar red"), std::string::npos) << head;
  EXPECT_NE(face_part.find("property float quality"), std::string::npos) << head;
  fs::remove_all(out.parent_path());
}

TEST(Meshlabserver, SupportSlimmingScriptOnTheBunny) {
  const std::string in = test::sample_bunny_path();
  const fs::path out = scratch("bunny_slimmed.ply");
  const test::ServerRun run = test::run_meshlabserver(
      "-i '" + in + "' -o '" + out.string() + "' -m fq fc vq sa -s '" + test::source_dir() + "/examples/support_slimming.mlx'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_EQ(run.output.find("Problem with filter"), std::string::npos) << run.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex(R"(risky area ([0-9.eE+-]+) -> ([0-9.eE+-]+) mm\^2)"))) << run.output;
  const double before = std::stod(m[1]), after = std::stod(m[2]);
  EXPECT_LT(after, 0.95 * before);

  // meshlabserver saves the current layer: the new "slimmed" one, deformed, with face quality
  // whose negative part is the logged risky area.
  const Surface input = test::load_mesh(in);
  io::FaceExtras saved;
  const Surface result = io::load_surface(out.string(), &saved);
  ASSERT_EQ(result.F.rows(), input.F.rows());
  ASSERT_EQ(saved.quality.size(), input.F.rows());
  EXPECT_GT((result.V - input.V).cwiseAbs().maxCoeff(), 1e-3);
  const Eigen::VectorXd areas = face_areas(result);
  double risky = 0.0;
  for (Eigen::Index f = 0; f < areas.size(); ++f)
    if (saved.quality(f) < 0) risky += areas(f);
  EXPECT_NEAR(risky, after, 0.02 * after);
  fs::remove_all(out.parent_path());
}

TEST(Meshlabserver, PrintOrientationScriptOnTheBunny) {
  // meshlabserver saves the current layer, the new "oriented" one: the core's best pose of the
  // bunny, resting on z = 0, with face quality for that pose; the log lists five poses.
  const std::string in = test::sample_bunny_path();
  const fs::path out = scratch("bunny_oriented.ply");
  const test::ServerRun run = test::run_meshlabserver(
      "-i '" + in + "' -o '" + out.string() + "' -m fq fc sa -s '" + test::source_dir() + "/examples/print_orientation.mlx'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_EQ(run.output.find("Problem with filter"), std::string::npos) << run.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex(R"(support proxy[^)]*\) ([0-9.eE+-]+) -> ([0-9.eE+-]+) mm\^3)")))
      << run.output;
  const double before = std::stod(m[1]), after = std::stod(m[2]);
  EXPECT_LT(after, before);
  EXPECT_NE(run.output.find("5. support"), std::string::npos) << run.output;

  const Surface input = test::load_mesh(in);
  const OrientationResult core = optimize_orientation(input);
  EXPECT_NEAR(after, core.best.shadow_volume, 1e-3 * core.best.shadow_volume);
  io::FaceExtras saved;
  const Surface result = io::load_surface(out.string(), &saved);
  ASSERT_EQ(result.F, input.F);
  EXPECT_LT((result.V - apply_orientation(input, core.rotation).V).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_NEAR(result.V.col(2).minCoeff(), 0.0, 1e-5);
  ASSERT_EQ(saved.quality.size(), input.F.rows());
  PrintSetup o;
  o.plate = plate_rule_as_used(core);
  const OverhangReport pose = analyse_overhang(result, o);
  EXPECT_LT((saved.quality - pose.quality).cwiseAbs().maxCoeff(), 1e-3);
  fs::remove_all(out.parent_path());
}

TEST(Meshlabserver, FailingFilterExplainsItselfInTheLog) {
  // A point cloud: the filter must fail with its reason, and meshlabserver must not crash.
  const fs::path in = scratch("points.ply");
  {
    std::ofstream f(in);
    f << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "end_header\n0 0 0\n1 0 0\n0 1 0\n";
  }
  const test::ServerRun run = test::run_meshlabserver(
      "-i '" + in.string() + "' -o '" + scratch("out.ply").string() + "' -s '" + test::source_dir() +
      "/examples/overhang_analysis.mlx'");
  EXPECT_NE(run.output.find("no faces"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("Segmentation"), std::string::npos) << run.output;
  fs::remove_all(in.parent_path());
}
