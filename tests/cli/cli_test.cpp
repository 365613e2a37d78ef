// The support-slim CLI as a user runs it: formats in and out, the summary, and one-line errors.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "core/overhang.h"
#include "support/shapes.h"
#include "vcg_adapters/mesh_io.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {
struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

CliRun run_cli(const std::string& args) {
  const fs::path err = fs::temp_directory_path() / ("slim-cli-err-" + std::to_string(::getpid()));
  const std::string cmd = "'" SLIM_CLI_PATH "' " + args + " 2>'" + err.string() + "'";
  CliRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  fs::remove(err);
  return r;
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("slim-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}
}  // namespace

TEST(Cli, RoundTripsEveryFormatInTheInputsFrame) {
  const fs::path dir = scratch();
  // The arch, far from the origin: the output must stay where the input was.
  const Surface arch = test::transformed(test::refined(test::arch(), 2), Eigen::Matrix3d::Identity(), {500, -300, 0});
  for (const std::string ext : {"ply", "stl", "obj", "off"}) {
    const fs::path in = dir / ("arch." + ext), out = dir / ("arch_slim." + ext);
    vcgx::save_surface(in.string(), arch);
    const CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --max-deviation 5 --quiet");
    ASSERT_EQ(r.exit_code, 0) << ext << ": " << r.err;
    EXPECT_NE(r.out.find("risky area"), std::string::npos) << r.out;
    const Surface back = vcgx::load_surface(out.string());
    EXPECT_EQ(back.F.rows(), arch.F.rows()) << ext;
    EXPECT_NEAR(back.V.col(0).mean(), arch.V.col(0).mean(), 2.0) << ext;  // no recentring
    EXPECT_NEAR(back.V.col(2).minCoeff(), 0.0, 1e-3) << ext;              // still on the plate
    const double diag = (arch.V.colwise().maxCoeff() - arch.V.colwise().minCoeff()).norm();
    EXPECT_NEAR((back.V.colwise().maxCoeff() - back.V.colwise().minCoeff()).norm(), diag, 0.1 * diag) << ext;
    EXPECT_LT(analyse_overhang(back).risky_area, analyse_overhang(arch).risky_area) << ext;
  }
  fs::remove_all(dir);
}

TEST(Cli, PlyOutputCarriesQualityAndTheStillRiskySelection) {
  const fs::path dir = scratch();
  const fs::path out = dir / "bunny.ply";
  const CliRun r = run_cli("'" + test::sample_bunny_path() + "' -o '" + out.string() + "' --method paper --iterations 3 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  vcgx::FaceExtras extras;
  const Surface back = vcgx::load_surface(out.string(), &extras);
  ASSERT_EQ(extras.quality.size(), back.F.rows());
  ASSERT_EQ(extras.selected.size(), static_cast<size_t>(back.F.rows()));
  for (Eigen::Index f = 0; f < back.F.rows(); ++f) EXPECT_EQ(extras.selected[static_cast<size_t>(f)], extras.quality(f) < 0);
  fs::remove_all(dir);
}

TEST(Cli, FeaturesFileIsRead) {
  const fs::path dir = scratch();
  const fs::path ids = dir / "ids.txt", out = dir / "out.ply";
  std::ofstream(ids) << "0 1 2\n3\n";
  CliRun r = run_cli("'" + test::sample_bunny_path() + "' -o '" + out.string() + "' --features '" + ids.string() + "' --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ofstream(ids) << "0 99999999\n";
  r = run_cli("'" + test::sample_bunny_path() + "' -o '" + out.string() + "' --features '" + ids.string() + "' --quiet");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("face 99999999"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, BadInputExitsNonZeroWithOneLine) {
  const fs::path dir = scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "'";
  const std::string out = " -o '" + (dir / "o.ply").string() + "'";
  for (const std::string& args : {std::string(""), bunny, bunny + out + " --angle 95", bunny + out + " --angle abc",
                                 bunny + out + " --dir 0,0,0", bunny + out + " --domain cubes",
                                 "'" + (dir / "missing.ply").string() + "'" + out, bunny + out + " --resolution 100000",
                                 bunny + out + " --frobnicate"}) {
    const CliRun r = run_cli(args + " --quiet");
    EXPECT_EQ(r.exit_code, 1) << args;
    ASSERT_FALSE(r.err.empty()) << args;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << args << ": " << r.err;  // exactly one line
    EXPECT_EQ(r.err.rfind("support-slim: ", 0), 0u) << r.err;
  }
  const CliRun help = run_cli("--help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* flag : {"--angle", "--dir", "--resolution", "--domain", "--iterations", "--method", "--max-deviation", "--threads"})
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
  fs::remove_all(dir);
}
