// 3MF between support-slim and the real PrusaSlicer: a part PrusaSlicer's command line exports as
// 3MF (placed off the origin by its build item) is slimmed by support-slim into a 3MF, and
// PrusaSlicer reads that back with the part where support-slim put it: the same bounding box,
// volume and facet count as the result written as STL, on the plate, with the placement kept.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "print_frame.h"
#include "key_values.h"
#include "mesh_io/mesh_io.h"
#include "run_command.h"
#include "support/shapes.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

// "key = value" lines of `prusa-slicer --info`.
std::map<std::string, double> slicer_info(const fs::path& file) {
  const test::CommandRun run = test::run_command("prusa-slicer --info " + test::shell_quote(file.string()) + " 2>/dev/null");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  std::map<std::string, double> info;
  static const std::regex line(R"re(^\s*([a-z_]+)\s*=\s*([-0-9.eE+]+)\s*$)re");
  std::smatch m;
  std::istringstream lines(run.output);
  for (std::string text; std::getline(lines, text);)
    if (std::regex_match(text, m, line)) info[m[1]] = std::stod(m[2]);
  return info;
}

test::CommandRun support_slim(const std::string& args) {
  return test::run_command(test::shell_quote(std::string(SLIM_BINARY_DIR) + "/cli/support-slim") + " " + args + " 2>&1");
}

}  // namespace

TEST(ThreeMfSlicer, PrusaSlicersThreeMfComesBackWhereSupportSlimPutIt) {
  const fs::path dir = test::scratch_dir(SLIM_EVAL_OUT_DIR, "threemf_slicer");
  const eval::PrintFrame f = eval::to_print_frame(test::sample_bunny(), Eigen::Vector3d::UnitZ(), 60.0);
  io::save_surface((dir / "bunny.stl").string(), f.surface);
  const test::CommandRun exported = test::run_command("cd " + test::shell_quote(dir.string()) +
                                                      " && prusa-slicer --export-3mf --center 70,90 -o bunny.3mf bunny.stl 2>&1");
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const io::MeshFile given = io::read_mesh((dir / "bunny.3mf").string());
  ASSERT_EQ(given.build.parts.size(), 1u);
  EXPECT_GT(given.build.parts[0].transform.col(3).norm(), 50.0);  // placed by its item, off the origin

  const std::string in = test::shell_quote((dir / "bunny.3mf").string());
  const test::CommandRun to_3mf = support_slim(in + " -o " + test::shell_quote((dir / "slim.3mf").string()));
  ASSERT_EQ(to_3mf.exit_code, 0) << to_3mf.output;
  const test::CommandRun to_stl = support_slim(in + " -o " + test::shell_quote((dir / "slim.stl").string()) + " --quiet");
  ASSERT_EQ(to_stl.exit_code, 0) << to_stl.output;

  const Surface result = io::load_surface((dir / "slim.stl").string());
  ASSERT_GT((result.V - given.surface.V).cwiseAbs().maxCoeff(), 0.1);  // the part was reshaped
  const Eigen::RowVector3d lo = result.V.colwise().minCoeff(), hi = result.V.colwise().maxCoeff();
  const std::map<std::string, double> info = slicer_info(dir / "slim.3mf");
  const char* axes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(info.at(std::string("min_") + axes[a]), lo(a), 1e-3) << axes[a];
    EXPECT_NEAR(info.at(std::string("max_") + axes[a]), hi(a), 1e-3) << axes[a];
  }
  EXPECT_EQ(info.at("number_of_facets"), double(result.F.rows()));
  EXPECT_NEAR(info.at("volume"), signed_volume(result), 1e-4 * signed_volume(result));
  // and its build item still places it: the object's own coordinates stay about its origin
  const io::MeshFile back = io::read_mesh((dir / "slim.3mf").string());
  ASSERT_EQ(back.build.parts.size(), 1u);
  EXPECT_LT((back.build.parts[0].transform - given.build.parts[0].transform).cwiseAbs().maxCoeff(), 1e-4);
}
