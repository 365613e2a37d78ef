// The bad-input catalogue through the core: every bad input (support/bad_inputs.h) ends in a
// sane result or a refusal that says what was wrong and what to change; plus the guards that the
// catalogue cannot express (scale invariance, the optimizer's memory guard, cancel, exceptions in
// parallel regions).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/domain/embedding.h"
#include "core/domain/tetgen_domain.h"
#include "core/domain/voxel_domain.h"
#include "core/optimizer/slimming.h"
#include "core/platform/parallel_for.h"
#include "core/print/overhang.h"
#include "support/bad_inputs.h"
#include "support/free_to_move.h"
#include "support/shapes.h"
#ifdef SLIM_TESTS_HAVE_VCG
#include "mesh_io/mesh_io.h"
#endif

using namespace slim;
using test::BadInput;
using test::mentions;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What Support Slimming should refuse with in this build ("" = nothing): a build without TetGen
// refuses every TetGen run that gets that far.
std::pair<std::string, std::string> expected_refusal(const BadInput& c) {
  if (c.options.domain == DomainKind::TetGen && !tetgen_available() && !mentions(c.refusal, "no face"))
    return {"without TetGen", "voxel domain"};
  return {c.refusal, c.advice};
}

class BadInputCore : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputCore, SupportSlimmingIsSaneOrRefusesWithAReason) {
  const BadInput& c = GetParam();
  const auto [refusal, advice] = expected_refusal(c);
  SlimmingOptions o = c.options;
  o.threads = 2;  // parallel regions run threaded, as in MeshLab
  if (!refusal.empty()) {
    try {
      slim_supports(c.surface, o);
      ADD_FAILURE() << c.name << ": expected a refusal mentioning '" << refusal << "'";
    } catch (const std::exception& e) {
      EXPECT_TRUE(mentions(e.what(), refusal)) << c.name << ": " << e.what();
      EXPECT_TRUE(mentions(e.what(), advice)) << c.name << " does not say what to change: " << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
    return;
  }
  const SlimmingResult r = slim_supports(c.surface, o);
  EXPECT_EQ(test::slimming_result_problem(c.surface, o, r), "") << c.name;
  EXPECT_EQ(r.inside_out, c.inside_out) << c.name;
  if (c.risky_before >= 0.0) {
    EXPECT_NEAR(r.before.risky_area, c.risky_before, 1e-6 * r.before.total_area) << c.name;
  }
}

TEST_P(BadInputCore, OverhangAnalysisIsSaneOrRefusesWithAReason) {
  const BadInput& c = GetParam();
  PrintSetup o;
  o.direction = c.options.print.direction;
  o.alpha_max_deg = c.options.print.alpha_max_deg;
  const Surface& s = c.surface;
  try {
    const OverhangReport r = analyse_overhang(inside_out(s, edge_topology(s)) ? flipped(s) : s, o);
    EXPECT_EQ(c.analysis_refusal, "") << c.name << " was analysed";
    EXPECT_TRUE(r.quality.allFinite());
    EXPECT_GE(r.risky_area, 0.0);
    EXPECT_LE(r.risky_area, r.total_area * (1 + 1e-12));
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(c.analysis_refusal, "") << c.name << ": " << e.what();
    EXPECT_TRUE(mentions(e.what(), c.analysis_refusal)) << c.name << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputCore, ::testing::ValuesIn(test::bad_inputs()),
                         [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

}  // namespace

TEST(Robustness, ResultDoesNotDependOnScaleOrPosition) {
  // The same arch at 1e-3 mm, 50 mm and 1e6 mm, and 1e5 mm from the origin: every tolerance of
  // the optimizer is relative, so the share of risky area left must match. The support model is
  // not: it counts a slicer's lengths (0.2 mm layers, 2.86 mm cells), so a part's support does not
  // scale with it, and the default choice of iterate by it is left out here (the shadow volume
  // chooses); ResultDoesNotDependOnPosition has it in. The arch is free to move
  // (test::free_to_move), so that its crown rises and the result differs from the input.
  SlimmingOptions o = test::free_to_move();
  o.steps.max_iterations = 10;
  o.result.judge = ResultJudge::ShadowVolume;
  const SlimmingResult base = slim_supports(test::arch(), o);
  ASSERT_LT(base.after.risky_share(), base.before.risky_share());
  for (const auto& [name, scale, shift] : {std::make_tuple("tiny", 2e-5, 0.0), std::make_tuple("huge", 2e4, 0.0),
                                           std::make_tuple("far", 1.0, 1e5)}) {
    const Surface s =
        test::transformed(test::arch(), scale * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Constant(shift));
    const SlimmingResult r = slim_supports(s, o);
    EXPECT_NEAR(r.after.risky_share(), base.after.risky_share(), 1e-3) << name;
    EXPECT_EQ(r.iterations, base.iterations) << name;
    EXPECT_NEAR(r.shape.volume_result / r.shape.volume_input, base.shape.volume_result / base.shape.volume_input, 1e-6) << name;
  }
}

TEST(Robustness, ResultDoesNotDependOnPosition) {
  // With the defaults, the support model's choice included: its grid is centred on the part's
  // bounding box and its figure averaged over grid phases, so moving the part changes nothing.
  // The arch is free to move (held to its height, its crown saves under the least saving).
  const Surface arch = test::refined(test::arch(), 3);
  const SlimmingOptions o = test::free_to_move();
  const SlimmingResult base = slim_supports(arch, o);
  ASSERT_LT(base.support_after_mm3.value(), base.support_before_mm3.value());
  const SlimmingResult far = slim_supports(test::transformed(arch, Eigen::Matrix3d::Identity(), {1e3, -2e3, 0.0}), o);
  EXPECT_EQ(far.iterations, base.iterations);
  EXPECT_NEAR(far.support_after_mm3.value(), base.support_after_mm3.value(), 1e-6 * base.support_before_mm3.value());
  EXPECT_NEAR(far.after.risky_share(), base.after.risky_share(), 1e-6);
}

TEST(Robustness, SignedVolumeKeepsItsDigitsFarFromTheOrigin) {
  const Surface t = test::t_shape();
  const Surface far = test::transformed(t, Eigen::Matrix3d::Identity(), {1e6, -1e6, 1e6});
  EXPECT_NEAR(signed_volume(far), signed_volume(t), 1e-9 * signed_volume(t));
}

TEST(Robustness, InsideOutMeshIsComputedTurnedOver) {
  // Turned over, the same part: the same positions, and the input's faces kept.
  SlimmingOptions o;
  o.steps.max_iterations = 5;
  const Surface t = test::t_shape();
  const SlimmingResult right = slim_supports(t, o), inverted = slim_supports(flipped(t), o);
  EXPECT_FALSE(right.inside_out);
  EXPECT_TRUE(inverted.inside_out);
  EXPECT_EQ(inverted.surface.V, right.surface.V);
  EXPECT_EQ(inverted.surface.F, flipped(t).F);
  EXPECT_EQ(inverted.before.risky_area, right.before.risky_area);
  // An open mesh has no inside: turned over it is simply another mesh, not inside out.
  const Surface bowl = test::open_hemisphere(2);
  EXPECT_FALSE(inside_out(flipped(bowl), edge_topology(flipped(bowl))));
}

TEST(Robustness, NonUnitPrintDirectionGivesTheSameResult) {
  SlimmingOptions unit, long_one;
  unit.steps.max_iterations = long_one.steps.max_iterations = 5;
  unit.print.direction = Eigen::Vector3d(0.2, 0.1, 1.0).normalized();
  long_one.print.direction = 7.0 * unit.print.direction;
  const Surface t = test::t_shape();
  EXPECT_EQ(slim_supports(t, unit).surface.V, slim_supports(t, long_one).surface.V);
}

TEST(Robustness, AbsurdResolutionsAreRefusedAtOnce) {
  for (int resolution : {1000000, 2147483647}) {
    SlimmingOptions o;
    o.resolution = resolution;
    const auto start = std::chrono::steady_clock::now();
    try {
      slim_supports(test::t_shape(), o);
      ADD_FAILURE() << resolution << " was accepted";
    } catch (const DomainTooLarge& e) {
      EXPECT_TRUE(mentions(e.what(), "at most")) << e.what();
      EXPECT_GE(e.fitting_resolution, 24);
    }
    EXPECT_LT(seconds_since(start), 1.0) << resolution;
  }
}

TEST(Robustness, OptimizerMemoryGuardRefusesBeforeAllocating) {
  // The domain fits the voxel guard, the optimizer does not fit its budget: refused with a
  // resolution that does fit, which then runs.
  SlimmingOptions o;
  o.resolution = 48;
  o.steps.max_iterations = 1;
  o.guards.max_memory_bytes = 20e6;
  int fitting = 0;
  try {
    slim_supports(test::t_shape(), o);
    FAIL() << "a 48-cell domain fitted 20 MB";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    ASSERT_TRUE(mentions(what, "memory budget")) << what;
    const size_t at = what.find("at most ");
    ASSERT_NE(at, std::string::npos) << what;
    fitting = std::stoi(what.substr(at + 8));
  }
  EXPECT_GT(fitting, 1);
  EXPECT_LT(fitting, 48);
  o.resolution = fitting;
  EXPECT_NO_THROW(slim_supports(test::t_shape(), o)) << "the suggested resolution " << fitting;
}

TEST(Robustness, CancelAtAnyProgressReportStopsAtOnce) {
  // A full run's reports; then a run cancelled at each of them stops there, with no result and
  // no further report. The stages between reports are short: domain, embedding, factorization,
  // one iteration each.
  SlimmingOptions o;
  o.steps.max_iterations = 6;
  int calls = 0;
  o.progress = [&](double, const std::string&) { return ++calls > 0; };
  const SlimmingResult full = slim_supports(test::t_shape(), o);
  const int total = calls;
  EXPECT_GE(total, full.iterations_run + 4) << "a report before the domain, the embedding, the factorization, "
                                               "after each iteration and at the end";
  for (int stop = 1; stop <= total; ++stop) {
    calls = 0;
    o.progress = [&](double, const std::string&) { return ++calls < stop; };
    EXPECT_THROW(slim_supports(test::t_shape(), o), Cancelled) << stop;
    EXPECT_EQ(calls, stop);
  }
}

TEST(Robustness, ExceptionInAParallelLoopReachesTheCaller) {
#ifdef _OPENMP
  const int previous = omp_get_max_threads();
  omp_set_num_threads(2);
#endif
  // The lowest failing index wins, whichever thread got there first; no std::terminate.
  int ran = 0;
  try {
    parallel_for(1000, [&](int i) {
      if (i == 37 || i == 900) throw std::runtime_error("failed at " + std::to_string(i));
#pragma omp atomic
      ++ran;
    });
    ADD_FAILURE() << "nothing was thrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "failed at 37");
  }
  EXPECT_EQ(ran, 998);
  // A real parallel region of the core: the embedding of a surface (over 8,192 vertices, so
  // threaded) into a domain too small for it fails inside the region and reports the first vertex.
  const Surface sphere = test::icosphere(5, 10.0);
  const VoxelDomain small = voxel_domain(test::box({-5, -5, 5}, {5, 5, 15}), Eigen::Vector3d::UnitZ());
  ASSERT_GT(sphere.V.rows(), 8192);
  try {
    embed_surface(sphere, small);
    ADD_FAILURE() << "the sphere fitted a smaller box";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(mentions(e.what(), "lies outside the tet domain")) << e.what();
  }
#ifdef _OPENMP
  omp_set_num_threads(previous);
#endif
}

TEST(Robustness, NeedleFacesAreEmbeddedNotRefused) {
  // A sliver whose area clipping cannot resolve (its width is at rounding level for the grid)
  // was refused as "partly outside the tet domain". Its lost area now goes to its largest piece.
  const Surface t = test::t_shape();
  for (double width : {1e-9, 1e-12, 1e-14, 1e-16}) {
    Surface s = t;
    const int n = static_cast<int>(t.V.rows());
    s.V.conservativeResize(n + 3, 3);
    s.V.bottomRows(3) << -20, 1, 23, 20, 1, 23, 20.0 / 3.0, 1 + width, 23;
    s.F.conservativeResize(t.F.rows() + 1, 3);
    s.F.bottomRows(1) << n, n + 1, n + 2;
    const VoxelDomain dom = voxel_domain(s, Eigen::Vector3d::UnitZ());
    const Embedding e = embed_surface(s, dom);
    double pieces = 0.0;
    for (Eigen::Index p = 0; p < e.tet_faces.size(); ++p)
      if (e.tet_faces(p) == t.F.rows()) pieces += e.tet_face_areas(p);
    // To the rounding of grid coordinates, which is all a needle's area is made of.
    const double diag = (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm();
    const double rounding = 64 * std::numeric_limits<double>::epsilon() * diag * diag;
    EXPECT_NEAR(pieces, face_areas(s)(t.F.rows()), 1e-6 * face_areas(s)(t.F.rows()) + rounding) << width;
  }
  // Truly outside stays an error.
  EXPECT_THROW(embed_surface(test::box({0, 0, 0}, {20, 20, 20}), voxel_domain(test::box({0, 0, 0}, {10, 10, 10}),
                                                                                 Eigen::Vector3d::UnitZ())),
               std::invalid_argument);
}

#ifdef SLIM_TESTS_HAVE_VCG
TEST(Robustness, MalformedMeshFilesAreRefusedNotCrashed) {
  // What the CLI reads: every file of the bad-file catalogue (support/bad_inputs.h) is refused
  // with "cannot read <file>: <why>", in process (and so under the sanitizers); a well-formed
  // ASCII STL loads into a surface the core can check.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("slim-robust-io-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const test::BadFile& f : test::bad_files()) {
    const std::string path = (dir / (f.name + "." + f.extension)).string();
    std::ofstream(path, std::ios::binary) << f.bytes;
    try {
      const Surface s = io::load_surface(path);
      ADD_FAILURE() << f.name << " loaded (" << s.V.rows() << " vertices, " << s.F.rows() << " faces)";
    } catch (const std::runtime_error& e) {
      EXPECT_TRUE(mentions(e.what(), path)) << e.what();
      EXPECT_TRUE(mentions(e.what(), f.refusal)) << f.name << ": " << e.what();
    }
  }
  const std::string ascii = (dir / "ascii.stl").string();
  std::ofstream(ascii) << "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 1\nendloop\n"
                          "endfacet\nendsolid\n";
  check_surface(io::load_surface(ascii));
  EXPECT_THROW(io::load_surface((dir / "missing.stl").string()), std::runtime_error);
  fs::remove_all(dir);
}
#endif
