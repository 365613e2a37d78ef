// The support-slim CLI as a user runs it: formats in and out, the summary, and one-line errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "core/optimizer/slimming.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "mesh_io/mesh_io.h"
#include "support/bad_inputs.h"
#include "support/shapes.h"

using namespace slim;
using test::mentions;
namespace fs = std::filesystem;

using test::CliRun;
using test::run_cli;
using test::scratch;

TEST(Cli, RoundTripsEveryFormatInTheInputsFrame) {
  const fs::path dir = scratch();
  // The arch, far from the origin: the output must stay where the input was.
  const Surface arch = test::transformed(test::refined(test::arch(), 2), Eigen::Matrix3d::Identity(), {500, -300, 0});
  for (const std::string ext : {"ply", "stl", "obj", "off"}) {
    const fs::path in = dir / ("arch." + ext), out = dir / ("arch_slim." + ext);
    io::save_surface(in.string(), arch);
    // Any saving will do (--min-saving 0): this small arch saves under the default's 3%.
    const CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --max-deviation 5 --min-saving 0 --quiet");
    ASSERT_EQ(r.exit_code, 0) << ext << ": " << r.err;
    EXPECT_NE(r.out.find("risky area"), std::string::npos) << r.out;
    const Surface back = io::load_surface(out.string());
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
  io::FaceExtras extras;
  const Surface back = io::load_surface(out.string(), &extras);
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
  EXPECT_EQ(r.exit_code, 2);  // bad usage
  EXPECT_NE(r.err.find("face 99999999"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, OrientTurnsThePartFirstAndSlimsItInItsPrintPose) {
  // The printable mushroom upside down and off the origin: --orient turns it cap up (onto its
  // stem's foot), --oriented-output holds that pose, and the slimmed OUT is in the same pose,
  // its displacement measured from the oriented part (the deformation, not the turn).
  const fs::path dir = scratch();
  const Surface upside_down =
      test::transformed(test::refined(test::printable_mushroom(), 1), test::axis_angle({1, 0, 0}, M_PI), {40, 5, 20});
  const fs::path in = dir / "mushroom.ply", out = dir / "slimmed.ply", posed = dir / "oriented.ply";
  io::save_surface(in.string(), upside_down);
  const CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --orient --oriented-output '" +
                           posed.string() + "' --iterations 3 --quiet --verbose");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* line : {"orientation     print direction (", "turned 180.0 deg", "support proxy", "(as given) ->",
                           "(oriented) ->", "(slimmed)", "1. support", "as given: support", "poses judged"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing from\n" << r.out;

  const Surface read_in = io::load_surface(in.string());
  const Surface expected = apply_orientation(read_in, optimize_orientation(read_in).rotation);
  const Surface oriented = io::load_surface(posed.string()), slimmed = io::load_surface(out.string());
  ASSERT_EQ(oriented.F, read_in.F);
  EXPECT_LT((oriented.V - expected.V).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_NEAR(oriented.V.col(2).minCoeff(), 0.0, 1e-5);
  EXPECT_NEAR(oriented.V.col(2).maxCoeff(), 20.0, 1e-4);  // the dome's apex on top
  EXPECT_EQ(analyse_overhang(oriented).risky_area, 0.0);  // cap up nothing overhangs
  ASSERT_EQ(slimmed.V.rows(), oriented.V.rows());
  EXPECT_EQ(slimmed.V, oriented.V);  // nothing left to slim

  // The bunny still overhangs in its best pose, so slimming moves it (10 iterations: by the support
  // model the first few save nothing yet, and --min-saving 0 takes any saving); the reported
  // displacement is the distance from the oriented part.
  const fs::path bunny_out = dir / "bunny.ply", bunny_posed = dir / "bunny_oriented.ply";
  const CliRun b = run_cli("'" + test::sample_bunny_path() + "' -o '" + bunny_out.string() + "' --orient --oriented-output '" +
                           bunny_posed.string() + "' --iterations 10 --min-saving 0 --quiet");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const Surface bunny_oriented = io::load_surface(bunny_posed.string()), bunny_slimmed = io::load_surface(bunny_out.string());
  ASSERT_EQ(bunny_slimmed.V.rows(), bunny_oriented.V.rows());
  const double moved = (bunny_slimmed.V - bunny_oriented.V).rowwise().norm().maxCoeff();
  const size_t at = b.out.find("displacement    max ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_GT(moved, 0.0);
  EXPECT_NEAR(std::stod(b.out.substr(at + 20)), moved, 1e-4 + 1e-3 * moved) << b.out;
  EXPECT_NE(b.out.find("(the deformation alone, in the print pose)"), std::string::npos);
  fs::remove_all(dir);
}

// A saving under --min-saving (3% by default) is not worth a change of shape: the mushroom's rim
// saves 2-3% of its modelled support, so the file comes back as given and the summary says why;
// with --min-saving 0 the same run bends the rim.
TEST(Cli, ASmallSavingReturnsThePartAsGiven) {
  const fs::path dir = scratch();
  const fs::path in = dir / "mushroom.ply", out = dir / "mushroom_slim.ply";
  io::save_surface(in.string(), test::refined(test::mushroom(), 2));
  const Surface given = io::load_surface(in.string());
  // Free to stretch: held to its proportions, the cap's rim saves nothing at all.
  const CliRun kept = run_cli("'" + in.string() + "' -o '" + out.string() + "' --allow-stretch --quiet");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_EQ(io::load_surface(out.string()).V, given.V);
  EXPECT_NE(kept.out.find("worth a change of shape, so the input is returned unchanged"), std::string::npos) << kept.out;
  EXPECT_EQ(kept.out.rfind("support-slim: " + in.string() + " -> " + out.string() + ": returned unchanged: ", 0), 0u)
      << kept.out;  // the verdict comes first
  const CliRun any = run_cli("'" + in.string() + "' -o '" + out.string() + "' --allow-stretch --min-saving 0 --quiet");
  ASSERT_EQ(any.exit_code, 0) << any.err;
  EXPECT_GT((io::load_surface(out.string()).V - given.V).cwiseAbs().maxCoeff(), 0.1);
  EXPECT_EQ(any.out.find("returned unchanged"), std::string::npos) << any.out;
  fs::remove_all(dir);
}

TEST(Cli, OrientOptionsAreChecked) {
  const std::string bunny = "'" + test::sample_bunny_path() + "' -o /tmp/never-written.ply ";
  for (const auto& [args, reason] : std::vector<std::pair<std::string, std::string>>{
           {"--orient --dir 0,0,1", "leave out --dir"},
           {"--oriented-output x.ply", "--oriented-output needs --orient"},
           {"--orient --orient-effort huge", "--orient-effort expects fast, normal or thorough"},
           {"--orient --angle 90", "self-supporting angle"},
           {"--max-displacement -1", "mean displacement limit"},
           {"--method paper --allow-stretch", "the paper's method lets the part stretch"},
           {"--method paper --max-displacement 2", "the paper's method lets the part stretch"}}) {
    const CliRun r = run_cli(bunny + args + " --quiet");
    EXPECT_EQ(r.exit_code, 2) << args;  // bad usage
    EXPECT_NE(r.err.find(reason), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// A negative build plate tolerance is refused before any work, with or without the orientation
// search: no file is written and the reason is one line.
TEST(Cli, ANegativePlateToleranceIsRefused) {
  const fs::path dir = scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "' -o '" + (dir / "o.ply").string() + "' ";
  for (const std::string& args : {std::string("--plate-tolerance -1"), std::string("--orient --plate-tolerance -0.5")}) {
    const CliRun r = run_cli(bunny + args + " --quiet");
    EXPECT_EQ(r.exit_code, 2) << args;  // bad usage
    EXPECT_NE(r.err.find("the build plate tolerance must be >= 0 mm"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.ply")) << args;
  }
  fs::remove_all(dir);
}

// A typo's minus sign, a missing folder, a folder as the input or an unknown format is refused
// before any work: one line naming the reason, no progress printed (progress starts with the
// first stage), no file written, and the exit code says whose fault: 2 the usage, 3 the input.
TEST(Cli, BadValuesAndPathsAreRefusedBeforeAnyWork) {
  const fs::path dir = scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "'";
  const std::string out = " -o '" + (dir / "o.ply").string() + "'";
  for (const auto& [args, reason, code] : std::vector<std::tuple<std::string, std::string, int>>{
           {bunny + out + " --max-deviation -1", "--max-deviation expects a value >= 0 (0: no budget), got -1", 2},
           {bunny + out + " --threads -3", "--threads expects a value >= 0 (0: every core), got -3", 2},
           {bunny + out + " --scale 0", "--scale expects a value > 0, got 0", 2},
           {bunny + out + " --scale -2", "--scale expects a value > 0, got -2", 2},
           {bunny + " -o '" + (dir / "missing" / "o.ply").string() + "'", "its folder " + (dir / "missing").string() + " does not exist", 2},
           {bunny + " -o '" + dir.string() + "'", "it is a folder", 2},
           {bunny + " -o '" + (dir / "o.3ds").string() + "'", "unknown mesh format", 2},
           {bunny + out + " --orient --oriented-output '" + (dir / "missing" / "p.ply").string() + "'", "cannot write the oriented part", 2},
           {"'" + dir.string() + "'" + out, "it is a folder, not a mesh file", 3},
           {"'" + (dir / "missing.ply").string() + "'" + out, "no such file", 3}}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, code) << args;  // 2: bad usage, 3: bad input file
    EXPECT_NE(r.err.find(reason), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("support-slim: ", 0), 0u) << args << ": " << r.err;  // no progress before it
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.ply")) << args;
  }
  fs::remove_all(dir);
}

// The mesh is taken in millimetres at print size: a 2 mm part gets a warning naming the likely
// units, and --scale fixes it (the result is written at the new size).
TEST(Cli, ATinyPartIsWarnedAboutAndScaleFixesIt) {
  const fs::path dir = scratch();
  const Surface tiny = test::transformed(test::t_shape(), 0.05 * Eigen::Matrix3d::Identity());  // 2.5 mm across
  io::save_surface((dir / "tiny.ply").string(), tiny);
  const std::string in = "'" + (dir / "tiny.ply").string() + "' -o '";
  const CliRun warned = run_cli(in + (dir / "a.ply").string() + "' --iterations 0 --quiet");
  ASSERT_EQ(warned.exit_code, 0) << warned.err;
  EXPECT_NE(warned.out.find("units           WARNING: the part is"), std::string::npos) << warned.out;
  EXPECT_NE(warned.out.find("inches (x 25.4)"), std::string::npos) << warned.out;

  const CliRun scaled = run_cli(in + (dir / "b.ply").string() + "' --scale 25.4 --iterations 0 --quiet");
  ASSERT_EQ(scaled.exit_code, 0) << scaled.err;
  EXPECT_EQ(scaled.out.find("WARNING"), std::string::npos) << scaled.out;
  EXPECT_NE(scaled.out.find("scale           x 25.4 (--scale), the result too"), std::string::npos) << scaled.out;
  const Surface out = io::load_surface((dir / "b.ply").string());
  ASSERT_EQ(out.V.rows(), tiny.V.rows());
  EXPECT_LE((out.V - 25.4 * tiny.V).cwiseAbs().maxCoeff(), 1e-5 * 25.4 * tiny.V.cwiseAbs().maxCoeff());
  fs::remove_all(dir);
}

TEST(Cli, BadInputExitsNonZeroWithOneLine) {
  const fs::path dir = scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "'";
  const std::string out = " -o '" + (dir / "o.ply").string() + "'";
  const std::string missing = "'" + (dir / "missing.ply").string() + "'" + out;
  for (const auto& [args, code] : std::vector<std::pair<std::string, int>>{
           {"", 2}, {bunny, 2}, {bunny + out + " --angle 95", 2}, {bunny + out + " --angle abc", 2},
           {bunny + out + " --dir 0,0,0", 2}, {bunny + out + " --domain cubes", 2}, {bunny + out + " --max-creases -1", 2},
           {bunny + out + " --max-creases 2 --method paper", 2}, {bunny + out + " --min-saving -1", 2},
           {bunny + out + " --min-saving 100", 2}, {bunny + out + " --min-saving 3 --method paper", 2}, {missing, 3},
           {bunny + out + " --frobnicate", 2},
           {bunny + out + " --resolution 100000", 1}}) {  // the run's memory guard: a failed run
    const CliRun r = run_cli(args + " --quiet");
    EXPECT_EQ(r.exit_code, code) << args << ": " << r.err;
    ASSERT_FALSE(r.err.empty()) << args;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << args << ": " << r.err;  // exactly one line
    EXPECT_EQ(r.err.rfind("support-slim: ", 0), 0u) << r.err;
  }
  const CliRun help = run_cli("--help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* flag : {"--angle", "--dir", "--resolution", "--domain", "--iterations", "--method", "--max-deviation", "--max-creases", "--min-saving", "--threads", "--one-resolution", "--out-dir", "--colour", "--scale", "--version"})
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
  fs::remove_all(dir);
}

namespace {
// The CLI flags for a catalogue case's settings, and the features file its selection needs.
std::string cli_flags(const test::BadInput& c, const fs::path& dir) {
  const SlimmingOptions& o = c.options;
  std::ostringstream flags;
  flags.precision(17);
  flags << " --dir " << o.print.direction.x() << "," << o.print.direction.y() << "," << o.print.direction.z()
        << " --angle " << o.print.alpha_max_deg << " --resolution " << o.resolution << " --iterations " << o.steps.max_iterations
        << " --max-deviation " << o.budget.share_percent().value_or(0.0) << " --max-k " << o.steps.max_k
        << " --domain " << (o.domain == DomainKind::TetGen ? "tetgen" : "voxel")
        << " --method " << (o.method == SlimmingMethod::Paper ? "paper" : "coherent");
  if (c.preserve_selection) {
    const fs::path ids = dir / "features.txt";
    std::ofstream list(ids);
    for (size_t f = 0; f < o.rigid_features.size(); ++f)
      if (o.rigid_features[f]) list << f << "\n";
    flags << " --features '" << ids.string() << "'";
  }
  return flags.str();
}

class BadInputCli : public ::testing::TestWithParam<test::BadInput> {};
}  // namespace

// The bad-input catalogue through the CLI: every case as a PLY file (NaN and all) and flags. A
// refusal is one line naming the reason, exit code 2 for a bad setting, 3 for a bad mesh, 1 for
// one the run makes; a success writes a sane mesh.
TEST_P(BadInputCli, WritesASaneMeshOrExitsWithOneLine) {
  const test::BadInput& c = GetParam();
  const fs::path dir = scratch();
  const fs::path in = dir / (c.name + ".ply"), out = dir / (c.name + "_out.ply");
  test::write_ascii_ply(in.string(), c.surface);
  const CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "'" + cli_flags(c, dir) + " --quiet");
  if (!c.refusal.empty()) {
    // As the core's own checks classify the case: 2 for a bad setting, 3 for a mesh the run
    // refuses, otherwise 1 (a refusal in the run: TetGen's, the memory guard's).
    auto refuses = [](const auto& check) {
      try {
        check();
      } catch (const std::invalid_argument&) {
        return true;
      }
      return false;
    };
    const int expected = refuses([&] { validate_slimming_options(c.options, static_cast<long>(c.surface.F.rows())); }) ? 2
                         : refuses([&] { check_slimming_input(c.surface); })                                          ? 3
                                                                                                                       : 1;
    EXPECT_EQ(r.exit_code, expected) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // exactly one line
    EXPECT_EQ(r.err.rfind("support-slim: ", 0), 0u) << r.err;
    // A NaN setting never reaches the core: the flag's own parser names it.
    const bool nan_setting = !c.options.print.direction.allFinite() || std::isnan(c.options.print.alpha_max_deg) ||
                             std::isnan(c.options.budget.share_percent().value_or(0.0));
    const std::string reason = nan_setting ? "expects a number" : c.refusal;
    EXPECT_TRUE(mentions(r.err, reason)) << c.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(out));
  } else {
    ASSERT_EQ(r.exit_code, 0) << c.name << ": " << r.err;
    EXPECT_EQ(mentions(r.out, "inside out"), c.inside_out) << r.out;
    const Surface input = io::load_surface(in.string()), result = io::load_surface(out.string());
    ASSERT_EQ(result.F, input.F);
    ASSERT_TRUE(result.V.allFinite());
    PrintSetup o;
    o.direction = c.options.print.direction;
    o.alpha_max_deg = c.options.print.alpha_max_deg;
    const double diag = (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm();
    o.plate = PlateRule::within(1e-3 * diag);
    const Surface seen_in = c.inside_out ? flipped(input) : input, seen_out = c.inside_out ? flipped(result) : result;
    const OverhangReport was = analyse_overhang(seen_in, o), now = analyse_overhang(seen_out, o);
    EXPECT_LE(now.risky_area, was.risky_area + 1e-5 * was.total_area) << c.name;
    const double ulps = 1e-6 * std::max(diag, input.V.cwiseAbs().maxCoeff());  // the PLY holds floats
    const Eigen::Vector3d d = c.options.print.direction.normalized();
    EXPECT_GE((result.V * d).minCoeff(), (input.V * d).minCoeff() - ulps) << c.name;
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputCli, ::testing::ValuesIn(test::bad_inputs()),
                         [](const ::testing::TestParamInfo<test::BadInput>& info) { return info.param.name; });

// A write that fails says why, in the system's words: here a full disk (a .ply that is /dev/full).
TEST(Cli, AFailedWriteGivesTheSystemsReason) {
  const fs::path dir = scratch();
  const fs::path full = dir / "full.ply";
  fs::create_symlink("/dev/full", full);
  const CliRun r = run_cli("'" + test::sample_bunny_path() + "' -o '" + full.string() + "' --iterations 0 --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.err;  // the run failed after it started
  EXPECT_NE(r.err.find("cannot write " + full.string() + ": writing failed (No space left on device)"), std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  fs::remove_all(dir);
}
