// eval/studies/slice_support.sh end to end with the real slicers: each figure is the mean over the
// quarter turns, every turn is a real slicing of the turned part, and the turns are exact, so a
// part given already turned by a quarter has the same four figures and the same mean.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "core/support_model/support_model.h"
#include "gcode_extrusion.h"
#include "key_values.h"
#include "mesh_io/mesh_io.h"
#include "print_frame.h"
#include "run_command.h"
#include "support/shapes.h"
#include "support/source_paths.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) { return test::scratch_dir(SLIM_EVAL_OUT_DIR, name); }
std::map<std::string, double> parse_metrics(const std::string& text) { return test::parse_key_values(text); }

test::CommandRun slice(const fs::path& stl, const std::string& slicer, const fs::path& out, const std::string& more = "") {
  return test::run_command(test::shell_quote(test::source_dir() + "/eval/studies/slice_support.sh") + " " + test::shell_quote(stl.string()) +
                           " --slicer " + slicer + " --angle 45 --build " + test::shell_quote(SLIM_BINARY_DIR) + " --out " +
                           test::shell_quote(out.string()) + " " + more);
}

struct Extent {
  double support_mm3, dx, dy;
};
Extent measure(const fs::path& gcode) {
  std::ifstream in(gcode);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  const eval::GcodeExtrusion g = eval::measure_extrusion(in, [&](const eval::ExtrusionMove& m) {
    for (int a = 0; a < 2; ++a) {
      lo[a] = std::min({lo[a], m.from[a], m.to[a]});
      hi[a] = std::max({hi[a], m.from[a], m.to[a]});
    }
  });
  return {g.support_mm() * eval::filament_area(1.75), hi[0] - lo[0], hi[1] - lo[1]};
}

// The refined arch in the print frame (+Z up, on the plate, 60 mm), and the same turned by 90°.
fs::path write_arch(const fs::path& dir) {
  const eval::PrintFrame f = eval::to_print_frame(test::refined(test::arch(), 1), Eigen::Vector3d::UnitZ(), 60.0);
  const fs::path stl = dir / "arch.stl";
  io::save_surface(stl.string(), f.surface);
  return stl;
}

void expect_mean_of_turns(const std::string& slicer) {
  const fs::path dir = scratch("slice_support_" + slicer);
  const fs::path arch = write_arch(dir);
  const test::CommandRun run = slice(arch, slicer, dir / "plain");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::map<std::string, double> m = parse_metrics(run.output);

  double sum = 0.0, lo = 1e300, hi = 0.0;
  std::map<int, Extent> turn;
  for (int t : {0, 90, 180, 270}) {
    turn[t] = measure(dir / "plain" / (slicer + "_turn" + std::to_string(t) + ".gcode"));
    EXPECT_NEAR(m.at("support_mm3_turn" + std::to_string(t)), turn[t].support_mm3, 1e-4 * turn[t].support_mm3) << t;
    EXPECT_GT(turn[t].support_mm3, 1000.0) << t;  // the arch's opening needs support
    sum += turn[t].support_mm3;
    lo = std::min(lo, turn[t].support_mm3);
    hi = std::max(hi, turn[t].support_mm3);
  }
  EXPECT_NEAR(m.at("support_mm3"), sum / 4, 1e-4 * sum / 4);
  EXPECT_NEAR(m.at("support_mm3_min"), lo, 1e-4 * lo);
  EXPECT_NEAR(m.at("support_mm3_max"), hi, 1e-4 * hi);
  EXPECT_NEAR(m.at("spread_pct"), 100 * (hi - lo) / (sum / 4), 0.01);
  // Each turn slices the part turned: a quarter turn swaps the tool path's X and Y extents.
  EXPECT_GT(turn[0].dx, 1.5 * turn[0].dy);  // the arch is 60 long, 20 deep
  EXPECT_NEAR(turn[90].dx, turn[0].dy, 0.5);
  EXPECT_NEAR(turn[90].dy, turn[0].dx, 0.5);

  // The arch given already turned by a quarter: exactly the same four poses, so the same
  // figures (turn 0 of the turned arch is turn 90 of the arch) and the same mean. The files
  // list the same triangles in another order (the STL reader welds by position), which moves
  // PrusaSlicer's figure by about 1e-5: far below the turns' spread (a few percent).
  const fs::path turned = dir / "arch_turned.stl";
  const test::CommandRun t = test::run_command(test::shell_quote(SLIM_BINARY_DIR "/eval/slim-eval") + " turn " +
                                               test::shell_quote(arch.string()) + " " + test::shell_quote(turned.string()) +
                                               " --quarter-turns 1");
  ASSERT_EQ(t.exit_code, 0) << t.output;
  const test::CommandRun run2 = slice(turned, slicer, dir / "turned");
  ASSERT_EQ(run2.exit_code, 0) << run2.output;
  const std::map<std::string, double> m2 = parse_metrics(run2.output);
  EXPECT_NEAR(m2.at("support_mm3_turn0"), m.at("support_mm3_turn90"), 1e-3 * m.at("support_mm3_turn90"));
  EXPECT_NEAR(m2.at("support_mm3_turn270"), m.at("support_mm3_turn0"), 1e-3 * m.at("support_mm3_turn0"));
  EXPECT_NEAR(m2.at("support_mm3"), m.at("support_mm3"), 1e-3 * m.at("support_mm3"));
}

}  // namespace

TEST(SliceSupport, PrusaSlicerFigureIsTheMeanOfFourTurnedSlicings) { expect_mean_of_turns("prusa"); }

TEST(SliceSupport, CuraFigureIsTheMeanOfFourTurnedSlicings) { expect_mean_of_turns("cura"); }

TEST(SliceSupport, BothSlicersSeeTheSameOverhang) {
  // The same arch opening under both slicers' defaults: their support differs in pattern and
  // density, not in where it stands, so the figures agree within a factor of two.
  const fs::path dir = scratch("slice_support_both");
  const fs::path arch = write_arch(dir);
  const test::CommandRun p = slice(arch, "prusa", dir, "--turns 0"), c = slice(arch, "cura", dir, "--turns 0");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const double prusa = parse_metrics(p.output).at("support_mm3"), cura = parse_metrics(c.output).at("support_mm3");
  EXPECT_GT(cura, 0.5 * prusa);
  EXPECT_LT(cura, 2.0 * prusa);
  // PrusaSlicer's own total agrees with our sum of all extrusion.
  EXPECT_LT(parse_metrics(p.output).at("total_vs_slicer_pct"), 0.01);
}

TEST(SliceSupport, TheSupportModelReadsAnOpenMeshAsPrusaSlicerSlicesIt) {
  // A 20 mm box with a window in its side from 6.25 to 13.75 mm. PrusaSlicer closes gaps up to
  // 2 mm in a slice and drops the contours it cannot close: through a 5 mm window every slice is
  // empty, and the box above stands on support down to the slice below the window. Two 1.25 mm
  // windows are closed over: no support. Cura stitches wider gaps (up to 10 mm) and supports
  // neither: the model's gap is PrusaSlicer's (SupportModelOptions::slice_max_gap).
  const fs::path dir = scratch("slice_support_open");
  SupportModelOptions at_slicer_phase;  // the quarter turns keep the slicer's grid phase
  at_slicer_phase.grid_phases = 1;
  at_slicer_phase.turns = 2;
  for (const auto& [width, windows] : {std::pair<double, int>{5.0, 1}, std::pair<double, int>{1.25, 2}}) {
    SCOPED_TRACE(width);
    const Surface box = test::box_with_windows(width, windows);
    const fs::path stl = dir / ("box_" + std::to_string(windows) + ".stl");
    io::save_surface(stl.string(), box);
    const test::CommandRun p = slice(stl, "prusa", dir / ("prusa_" + std::to_string(windows)));
    ASSERT_EQ(p.exit_code, 0) << p.output;
    const double prusa = parse_metrics(p.output).at("support_mm3"), model = estimate_support(box, at_slicer_phase).volume_mm3;
    if (windows == 2) {
      EXPECT_LT(prusa, 1.0);
      EXPECT_LT(model, 1.0);
      continue;
    }
    EXPECT_GT(prusa, 1000.0);
    EXPECT_NEAR(model / prusa, 1.0, 0.15) << model << " against " << prusa;
    SupportModelOptions rays = at_slicer_phase;  // the faces as they are: no overhang at all
    rays.open_mesh_slices = false;
    EXPECT_LT(estimate_support(box, rays).volume_mm3, 1.0);
    const test::CommandRun c = slice(stl, "cura", dir / "cura", "--turns 0");
    ASSERT_EQ(c.exit_code, 0) << c.output;
    EXPECT_LT(parse_metrics(c.output).at("support_mm3"), 0.05 * prusa);
  }
}

// An inverted square pyramid, its corners on the axes at radius r, its underside rising at
// `slope` degrees from the apex at z = 5 to a 2 mm rim, on a 4 mm post: support under a sloped
// overhang (no bridge, which PrusaSlicer would leave out) whose island steps by a cell from one row
// of grid cells to the next along each side.
Surface inverted_pyramid_on_a_post(double r, double slope) {
  const double z0 = 5.0, rim = z0 + r * std::tan(slope * M_PI / 180.0), top = rim + 2.0;
  Surface s;
  s.V.resize(10, 3);
  s.V.row(0) << 0, 0, z0;
  s.V.row(9) << 0, 0, top;
  const double corner[4][2] = {{r, 0}, {0, r}, {-r, 0}, {0, -r}};
  for (int i = 0; i < 4; ++i) {
    s.V.row(1 + i) << corner[i][0], corner[i][1], rim;
    s.V.row(5 + i) << corner[i][0], corner[i][1], top;
  }
  s.F.resize(16, 3);
  for (int i = 0; i < 4; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % 4;
    s.F.row(4 * i) << 0, b, a;                     // the underside
    s.F.row(4 * i + 1) << a, b, b + 4;             // the rim
    s.F.row(4 * i + 2) << a, b + 4, a + 4;
    s.F.row(4 * i + 3) << 9, a + 4, b + 4;         // the top
  }
  return test::merge(s, test::box({-2, -2, 0}, {2, 2, z0 + 1.0}));
}

TEST(SliceSupport, TheSupportModelsBaseFollowsPrusaSlicersZigzagAlongASteppedOutline) {
  // PrusaSlicer joins its base fill lines at alternate ends by links along the island's outline,
  // out past the end of the shorter line and back where the outline steps. Under these pyramids
  // every row end steps: the model's base (fill, sheath and first layer) is PrusaSlicer's within
  // 3% (0.5% here), where without the links along the steps it was 13% under.
  const fs::path dir = scratch("slice_support_zigzag");
  SupportModelOptions at_slicer_phase;
  at_slicer_phase.grid_phases = 1;
  at_slicer_phase.turns = 2;
  for (double r : {18.5, 21.3}) {  // not a whole number of cells: no edge runs through cell corners
    SCOPED_TRACE(r);
    const Surface part = inverted_pyramid_on_a_post(r, 30.0);
    ASSERT_GT(signed_volume(part), 0.0);
    const fs::path stl = dir / ("pyramid_" + std::to_string(static_cast<int>(10 * r)) + ".stl");
    io::save_surface(stl.string(), part);
    const test::CommandRun p = slice(stl, "prusa", dir / ("prusa_" + std::to_string(static_cast<int>(10 * r))), "--turns 0,90");
    ASSERT_EQ(p.exit_code, 0) << p.output;
    const std::map<std::string, double> m = parse_metrics(p.output);
    const double prusa_base = m.at("support_mm3") - m.at("support_interface_mm3");
    const SupportEstimate e = estimate_support(part, at_slicer_phase);
    const double model_base = e.base_fill_mm3 + e.sheath_mm3 + e.first_layer_mm3;
    ASSERT_GT(prusa_base, 1000.0);
    EXPECT_NEAR(model_base / prusa_base, 1.0, 0.03) << model_base << " against " << prusa_base;
  }
}

TEST(SliceSupport, TheSupportModelSeesAFootsFlareWherePrusaSlicerDoes) {
  // A foot: radius 3 at the plate, flaring out, then a wall to 5 mm. A slicer sees an overhang in a
  // layer where the slice reaches past the one below by its margin; a contact under layer 1 would
  // lie under the first layer and is dropped. Flaring within the first two slices (to 0.32 mm), or
  // in steps that never reach the margin in one layer, the foot gets no support; flaring to 0.55
  // mm, it has a contact in the first layer alone, which PrusaSlicer takes out of the first layer
  // and prints nowhere; flaring over four layers (to 0.75 mm), it gets a first layer around it.
  const fs::path dir = scratch("slice_support_feet");
  SupportModelOptions at_slicer_phase;
  at_slicer_phase.grid_phases = 1;
  at_slicer_phase.turns = 2;
  const std::vector<std::vector<Eigen::Vector2d>> flares{
      {{3.35, 0.32}}, {{3.25, 0.25}, {3.25, 0.45}, {3.5, 0.6}}, {{3.65, 0.55}}, {{3.8, 0.75}}};
  for (size_t i = 0; i < flares.size(); ++i) {
    SCOPED_TRACE(i);
    const Surface foot = test::flared_foot(flares[i]);
    const fs::path stl = dir / ("foot_" + std::to_string(i) + ".stl");
    io::save_surface(stl.string(), foot);
    const test::CommandRun p = slice(stl, "prusa", dir / ("prusa_" + std::to_string(i)), "--turns 0,90");
    ASSERT_EQ(p.exit_code, 0) << p.output;
    const double prusa = parse_metrics(p.output).at("support_mm3"), model = estimate_support(foot, at_slicer_phase).volume_mm3;
    if (i < 3) {
      EXPECT_LT(prusa, 1.0);
      EXPECT_LT(model, 1.0);
    } else {
      EXPECT_GT(prusa, 20.0);
      EXPECT_NEAR(model / prusa, 1.0, 0.15) << model << " against " << prusa;
    }
  }
}

TEST(SliceSupport, WhereTheInterfaceReachesThePlateNeitherGrowsAFirstLayer) {
  // A 20 mm slab whose flat underside lies 1 mm over the plate, on a 4 mm stem: the three dense
  // interface layers under its contact fill the layers down to the plate. PrusaSlicer grows the
  // first layer's base by 3 mm and takes the interface out of it: here there is no base, so no
  // growth, only interface; so does the model.
  const fs::path dir = scratch("slice_support_low_slab");
  const Surface slab = test::merge(test::box({-2, -2, 0}, {2, 2, 1}), test::box({-10, -10, 1}, {10, 10, 3}));
  const fs::path stl = dir / "slab.stl";
  io::save_surface(stl.string(), slab);
  const test::CommandRun p = slice(stl, "prusa", dir / "prusa", "--turns 0");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  const std::map<std::string, double> m = parse_metrics(p.output);
  EXPECT_GT(m.at("support_mm3"), 100.0);
  EXPECT_NEAR(m.at("support_interface_mm3"), m.at("support_mm3"), 1e-6);
  SupportModelOptions at_slicer_phase;
  at_slicer_phase.grid_phases = 1;
  const SupportEstimate e = estimate_support(slab, at_slicer_phase);
  EXPECT_GT(e.top_interface_mm3, 100.0);
  EXPECT_EQ(e.first_layer_mm3, 0.0);
  EXPECT_EQ(e.base_fill_mm3 + e.sheath_mm3, 0.0);
}

TEST(SliceSupport, BadArgumentsFailWithAOneLineReason) {
  const fs::path dir = scratch("slice_support_bad");
  const fs::path arch = write_arch(dir);
  for (const std::string& args : {std::string("--slicer simplify3d"), std::string("--slicer prusa --turns 45"),
                                  std::string("--slicer cura --turns 0,"), std::string("--slicer prusa --jobs 0")}) {
    const test::CommandRun r = test::run_command(test::shell_quote(test::source_dir() + "/eval/studies/slice_support.sh") + " " +
                                                 test::shell_quote(arch.string()) + " --angle 45 --out " +
                                                 test::shell_quote((dir / "o").string()) + " " + args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.output.rfind("slice_support: ", 0), 0u) << args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << ": " << r.output;
  }
}
