// eval/studies/corpus.sh end to end on this machine: the packages fetched and unpacked, the models
// converted and turned into their print pose, every one with the faces docs/corpus.md lists and in
// one of the two halves (tune, check), each half with organic and CAD models. The
// corpus is what the frontier and the support model's validation are measured on; a reader change
// once made it stop at the spider (its slivers), unseen, because nothing built it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/orientation/orientation.h"
#include "core/support_model/support_model.h"
#include "key_values.h"
#include "mesh_io/mesh_io.h"
#include "run_command.h"
#include "support/shapes.h"
#include "support/source_paths.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

// The corpus, built once in the build tree (eval/studies/corpus.sh only checks it on a second run).
fs::path corpus_dir() { return fs::path(SLIM_EVAL_OUT_DIR) / "corpus"; }
test::CommandRun build_corpus() {
  return test::run_command(test::shell_quote(test::source_dir() + "/eval/studies/corpus.sh") + " --build " +
                           test::shell_quote(SLIM_BINARY_DIR) + " --out " + test::shell_quote(corpus_dir().string()));
}

}  // namespace

TEST(Corpus, EveryModelArrivesInItsPrintPoseWithItsFaces) {
  const fs::path out = corpus_dir();
  const test::CommandRun run = build_corpus();
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // docs/corpus.md's table: name -> faces.
  const std::map<std::string, long> expected = {
      // The real models the optimizer was tuned on.
      {"bunny", 3674}, {"bunny_70k", 69666}, {"horse", 7172}, {"knight", 7876}, {"suzanne", 3936}, {"wuson", 3732},
      {"duck", 4212}, {"spider", 1312}, {"scad_example001", 1264}, {"scad_example004", 880}, {"scad_example017", 1240},
      {"netgen_hinge", 1212},
      // The other real models: organic, then CAD.
      {"ant", 912}, {"apple", 1704}, {"asteroid", 48000}, {"cat", 14348}, {"chess_bishop", 3874}, {"chess_king", 10688},
      {"chess_pawn", 3024}, {"chess_queen", 10320}, {"chess_rook", 3056}, {"dinosaur", 6656}, {"dwarf", 1896},
      {"faerie", 654}, {"human", 8560}, {"md2_knight", 634}, {"md2_ogro", 670}, {"md2_rat", 666}, {"md2_rhino", 730},
      {"mrfixit", 2988}, {"rabbit", 1252}, {"sydney", 679},
      {"gear", 2880}, {"heartgears", 30636}, {"kr5_base", 996}, {"kr5_elbow", 964}, {"lever", 774}, {"mug", 24544},
      {"nut", 1046}, {"occt_bearing", 24680}, {"occt_gearbox", 26966}, {"occt_motor", 13506}, {"scad_example005", 1042},
      {"scad_example016", 556}, {"scad_example020", 8490},
      // The creatures.
      {"creature_quadruped", 17316}, {"creature_long_neck", 21056}, {"creature_upright", 15128}};
  std::ifstream manifest(out / "manifest.tsv");
  ASSERT_TRUE(manifest) << "no manifest.tsv";
  std::string line;
  std::getline(manifest, line);  // the header; the half is the last column
  EXPECT_EQ(line.substr(line.rfind('\t') + 1), "half") << line;
  std::map<std::string, long> faces;
  std::map<std::string, std::set<std::string>> kinds;  // half -> the kinds of its models
  while (std::getline(manifest, line)) {
    std::istringstream row(line);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(row, cell, '\t');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 11u) << line;
    const std::string &name = cells[0], &kind = cells[1], &half = cells[10];
    faces[name] = std::stol(cells[2]);
    EXPECT_TRUE(half == "tune" || half == "check") << name << ": half '" << half << "'";
    kinds[half].insert(kind);
  }
  EXPECT_EQ(faces, expected);
  // Each half holds organic and CAD models: what was tuned on one half is checked on the same kinds.
  for (const char* half : {"tune", "check"})
    for (const char* kind : {"organic", "cad"})
      EXPECT_EQ(kinds[half].count(kind), 1u) << "no " << kind << " model in the " << half << " half";
  for (const auto& [name, count] : expected) {
    SCOPED_TRACE(name);
    const Surface s = io::load_surface((out / (name + ".ply")).string());
    EXPECT_EQ(s.F.rows(), count);
    // The print pose: resting on the plate, the longest side 60 mm, outward (positive volume).
    const Eigen::RowVector3d lo = s.V.colwise().minCoeff(), hi = s.V.colwise().maxCoeff();
    EXPECT_NEAR(lo.z(), 0.0, 1e-9);
    EXPECT_NEAR((hi - lo).maxCoeff(), 60.0, 1e-6);
    EXPECT_GT(signed_volume(s), 0.0);
  }
  // The duck sits on its flat underside. On its side it casts less shadow, and the support model
  // gives it 0.1% less support, a tie within the model's noise; PrusaSlicer gives 4.3% more. A tie
  // goes to the pose resting more on the plate: Print Orientation leaves the duck as it is.
  const OrientationResult duck = optimize_orientation(io::load_surface((out / "duck.ply").string()));
  EXPECT_EQ(duck.best.direction, Eigen::Vector3d::UnitZ());
  bool tie = false;  // a turn the score prefers that the model cannot tell from the pose as given
  for (size_t k = 1; k < duck.top.size(); ++k) {
    const OrientationCandidate& c = duck.top[k];
    tie |= c.support_estimate && c.score < duck.as_given.score && c.contact_area < duck.as_given.contact_area &&
           *c.support_estimate <= duck.as_given.support_estimate.value() * 1.01 + 1.0;
  }
  EXPECT_TRUE(tie);
}

TEST(Corpus, TheSupportModelPredictsPrusaSlicersChangeOnTheHinge) {
  // The yardstick (the model's predicted change within 5 points of PrusaSlicer's) on the
  // corpus model it missed by 9: slimmed at the defaults, the hinge's bore ceiling turns from a
  // round one into one whose 45-degree facets are steeper. Its new lowest overhanging facet ends
  // 0.01 mm short of a grid row, and PrusaSlicer still supports that row: each layer's overhang
  // runs from the outline of the slice below, which lies on the steeper facet past the row's
  // edge, and a sliver of a contact reaches its cell. With both rules the model predicts -5.4%
  // where PrusaSlicer gives -3.6% (the mean of its quarter turns 0 and 90, the model's own
  // protocol); without them, on the result it chose then, it said -14.0% against -5.0%.
  ASSERT_EQ(build_corpus().exit_code, 0);
  const fs::path dir = test::scratch_dir(SLIM_EVAL_OUT_DIR, "hinge_change"), input = corpus_dir() / "netgen_hinge.ply";
  const fs::path result = dir / "result.ply";
  const test::CommandRun slim = test::run_command(test::shell_quote(SLIM_BINARY_DIR "/cli/support-slim") + " " +
                                                  test::shell_quote(input.string()) + " -o " + test::shell_quote(result.string()) +
                                                  " --dir 0,0,1 --angle 45 --plate-tolerance 0.071 --quiet");
  ASSERT_EQ(slim.exit_code, 0) << slim.output;
  SupportModelOptions judged;  // at the slicer's own grid phase, turns 0 and 90
  judged.grid_phases = 1;
  judged.turns = 2;
  double prusa[2], model[2];
  for (int k = 0; k < 2; ++k) {
    const Surface part = io::load_surface((k == 0 ? input : result).string());
    const fs::path stl = dir / (k == 0 ? "input.stl" : "result.stl");
    io::save_surface(stl.string(), part);
    const test::CommandRun sliced = test::run_command(
        test::shell_quote(test::source_dir() + "/eval/studies/slice_support.sh") + " " + test::shell_quote(stl.string()) +
        " --slicer prusa --angle 45 --turns 0,90 --build " + test::shell_quote(SLIM_BINARY_DIR) + " --out " +
        test::shell_quote((dir / (k == 0 ? "sliced_input" : "sliced_result")).string()));
    ASSERT_EQ(sliced.exit_code, 0) << sliced.output;
    prusa[k] = test::parse_key_values(sliced.output).at("support_mm3");
    model[k] = estimate_support(part, judged).volume_mm3;
  }
  const double prusa_change = 100.0 * (prusa[1] / prusa[0] - 1.0), model_change = 100.0 * (model[1] / model[0] - 1.0);
  EXPECT_LT(prusa_change, -1.0);  // the slimming saves some support, as PrusaSlicer counts it
  EXPECT_NEAR(model_change, prusa_change, 5.0) << "PrusaSlicer " << prusa[0] << " -> " << prusa[1] << " mm3, the model "
                                              << model[0] << " -> " << model[1];
}

TEST(Corpus, AnOpenScanFromRandomPosesIsOrientedAsPrusaSlicerSlicesIt) {
  // The knight is an open scan: PrusaSlicer closes the small gaps in its slices and prints it
  // upright with the least support (its ten other poses all need more). Read along rays it would
  // lie on its side. Turned at random three times (fixed seed), Print Orientation must bring it
  // back to a pose that PrusaSlicer (the mean of quarter turns 0 and 90) supports with at most 5%
  // more than upright. Upright is placed from the same turned input (rotation_to_up of its upright
  // direction), so both poses meet the slicer's grid at the same turn about the print axis: the
  // same upright knight turned about Z alone differs by up to 14% in PrusaSlicer.
  ASSERT_EQ(build_corpus().exit_code, 0);
  const fs::path dir = test::scratch_dir(SLIM_EVAL_OUT_DIR, "open_scan_orientation");
  const Surface knight = io::load_surface((corpus_dir() / "knight.ply").string());
  auto prusa_support = [&](const Surface& posed, const std::string& name) {
    const fs::path stl = dir / (name + ".stl");
    io::save_surface(stl.string(), posed);
    const test::CommandRun sliced = test::run_command(
        test::shell_quote(test::source_dir() + "/eval/studies/slice_support.sh") + " " + test::shell_quote(stl.string()) +
        " --slicer prusa --angle 45 --turns 0,90 --build " + test::shell_quote(SLIM_BINARY_DIR) + " --out " +
        test::shell_quote((dir / ("sliced_" + name)).string()));
    EXPECT_EQ(sliced.exit_code, 0) << sliced.output;
    return test::parse_key_values(sliced.output).at("support_mm3");
  };
  std::mt19937_64 gen(7);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::Matrix3d R = test::random_rotation(gen);
    const Surface turned = test::transformed(knight, R);
    const OrientationResult r = optimize_orientation(turned);
    const double oriented = prusa_support(apply_orientation(turned, r.rotation), "trial" + std::to_string(trial));
    const double upright =
        prusa_support(apply_orientation(turned, rotation_to_up(R * Eigen::Vector3d::UnitZ())), "upright" + std::to_string(trial));
    EXPECT_LE(oriented, 1.05 * upright) << "trial " << trial << ": direction " << r.best.direction.transpose() << " ("
                                        << r.best.origin << "), upright is " << (R * Eigen::Vector3d::UnitZ()).transpose();
  }
}
