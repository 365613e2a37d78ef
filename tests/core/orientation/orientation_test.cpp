// Print orientation: the score against a face-by-face reference, the search against brute force
// over its own candidates, known best poses, invariance under rotation, determinism, and the
// support model's verdict (refusals: orientation_bad_input_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "core/support_model/support_model.h"
#include "support/shapes.h"

using namespace slim;

namespace {

Eigen::Vector3d random_direction(std::mt19937_64& gen) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(gen), normal(gen), normal(gen)).normalized();
}

double part_size(const Surface& s) {
  const Eigen::RowVector3d centre = s.V.colwise().mean();
  return 2.0 * (s.V.rowwise() - centre).rowwise().norm().maxCoeff();
}

// The score of orientation.h written out from analyse_overhang, the project's overhang rule.
struct Reference {
  double shadow_volume, risky_area, contact_area, score;
};
Reference reference_score(const Surface& s, const Eigen::Vector3d& d, const OrientationOptions& o) {
  PrintSetup oo;
  oo.direction = d;
  oo.alpha_max_deg = o.alpha_max_deg;
  // The default tolerance is Support Slimming's: 1e-3 of the bbox diagonal of the part as given.
  oo.plate = PlateRule::within(o.plate.tolerance_mm(test::bbox_diagonal(s)).value());
  const OverhangReport r = analyse_overhang(s, oo);
  const Eigen::VectorXd area = face_areas(s);
  double contact = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (r.on_plate[static_cast<size_t>(f)]) contact += area(f);
  return {r.shadow_volume, r.risky_area, contact, r.shadow_volume - o.contact_bonus * part_size(s) * contact};
}

// The vertices' heights in the print pose, sorted: two poses of one part that differ only by a
// turn about Z, a shift on the plate or a mirror symmetry of the part give the same list.
Eigen::VectorXd sorted_heights(const Surface& s) {
  Eigen::VectorXd z = s.V.col(2);
  std::sort(z.data(), z.data() + z.size());
  return z;
}

struct NamedShape {
  std::string name;
  Surface surface;
};
std::vector<NamedShape> shapes() {
  std::vector<NamedShape> all{{"T", test::t_shape()},
                              {"mushroom", test::mushroom()},
                              {"printable mushroom", test::printable_mushroom()},
                              {"arch", test::arch()},
                              {"L-bracket", test::l_bracket()},
                              {"sphere", test::icosphere(3)},
                              {"box", test::box({0, 0, 0}, {10, 20, 30})}};
#ifdef SLIM_TESTS_HAVE_VCG
  all.push_back({"bunny", test::load_mesh(test::sample_bunny_path())});
#endif
  return all;
}

}  // namespace

TEST(Orientation, ScoreEqualsTheOverhangRuleFaceByFace) {
  std::mt19937_64 gen(1);
  for (const NamedShape& shape : shapes()) {
    const double scale = face_areas(shape.surface).sum() * part_size(shape.surface);
    // Random directions, and the axes, which rest the boxy shapes' faces on the plate.
    std::vector<Eigen::Vector3d> dirs;
    for (int k = 0; k < 20; ++k) dirs.push_back(random_direction(gen));
    for (int axis = 0; axis < 3; ++axis) dirs.push_back(Eigen::Vector3d::Unit(axis)), dirs.push_back(-Eigen::Vector3d::Unit(axis));
    for (double alpha : {0.0, 45.0, 70.0}) {
      OrientationOptions o;
      o.alpha_max_deg = alpha;
      for (const Eigen::Vector3d& d : dirs) {
        const OrientationCandidate c = score_orientation(shape.surface, 3.0 * d, o);  // any length
        const Reference r = reference_score(shape.surface, d, o);
        SCOPED_TRACE(shape.name + " alpha " + std::to_string(alpha));
        EXPECT_NEAR(c.shadow_volume, r.shadow_volume, 1e-12 * scale);
        EXPECT_NEAR(c.risky_area, r.risky_area, 1e-12 * scale);
        EXPECT_NEAR(c.contact_area, r.contact_area, 1e-12 * scale);
        EXPECT_NEAR(c.score, r.score, 1e-12 * scale);
        EXPECT_TRUE(c.direction.isApprox(d, 1e-15));
      }
    }
  }
}

TEST(Orientation, SearchIsNoWorseThanBruteForceOverItsCandidates) {
  // The sweep's binned arithmetic and its hull-walk plate only rank; whatever they rank, the best
  // pose returned must match the exact score of every sphere direction and the pose as given.
  // (The support model's final choice is off here: SupportModelPicksTheLeastSupportOfTheBest.)
  for (const NamedShape& shape : shapes()) {
    OrientationOptions o;
    o.sphere_candidates = 500;
    o.support_model_candidates = 0;
    const OrientationResult r = optimize_orientation(shape.surface, o);
    double brute = score_orientation(shape.surface, Eigen::Vector3d::UnitZ(), o).score;
    for (const Eigen::Vector3d& d : fibonacci_sphere(o.sphere_candidates))
      brute = std::min(brute, score_orientation(shape.surface, d, o).score);
    const double scale = face_areas(shape.surface).sum() * part_size(shape.surface);
    EXPECT_LE(r.best.score, brute + 1e-9 * scale) << shape.name;
    // And it is the exact score of the direction it names.
    EXPECT_NEAR(r.best.score, reference_score(shape.surface, r.best.direction, o).score, 1e-12 * scale) << shape.name;
    EXPECT_NEAR(r.as_given.score, reference_score(shape.surface, Eigen::Vector3d::UnitZ(), o).score, 1e-12 * scale)
        << shape.name;
    EXPECT_LE(r.best.score, r.as_given.score) << shape.name;
  }
}

TEST(Orientation, TopCandidatesAreSortedDistinctAndExact) {
  // With the score alone (no support model), the list is in the score's order. (By the model:
  // PoseJudging.TheListRanksByTheModelTheChosenFirst.)
  const Surface t = test::t_shape();
  OrientationOptions o;
  o.support_model_candidates = 0;
  const OrientationResult r = optimize_orientation(t, o);
  ASSERT_GE(r.top.size(), 3u);
  ASSERT_LE(static_cast<int>(r.top.size()), o.report_count);
  EXPECT_EQ(r.top.front().direction, r.best.direction);
  for (size_t i = 0; i < r.top.size(); ++i) {
    EXPECT_NEAR(r.top[i].direction.norm(), 1.0, 1e-12);
    EXPECT_NEAR(r.top[i].score, reference_score(t, r.top[i].direction, o).score, 1e-9);
    if (i > 0) {
      EXPECT_LE(r.top[i - 1].score, r.top[i].score + 1e-9);
    }
    for (size_t j = 0; j < i; ++j)
      EXPECT_GE(std::acos(std::clamp(r.top[i].direction.dot(r.top[j].direction), -1.0, 1.0)),
                o.distinct_deg * M_PI / 180.0 - 1e-12);
  }
}

TEST(Orientation, PrintableMushroomUpsideDownIsTurnedCapUp) {
  // Upside down it balances on its dome; cap up nothing overhangs and the stem's foot is on the
  // plate. The search must turn it back over: the print direction is the input's -Z.
  const Surface natural = test::printable_mushroom();
  const Surface upside_down = test::transformed(natural, test::axis_angle({1, 0, 0}, M_PI), {0, 0, 20});
  const OrientationResult r = optimize_orientation(upside_down);
  EXPECT_GT(r.as_given.shadow_volume, 100.0);
  EXPECT_LT(r.best.direction.dot(-Eigen::Vector3d::UnitZ()), 1.0 + 1e-12);
  EXPECT_GT(r.best.direction.dot(-Eigen::Vector3d::UnitZ()), std::cos(1e-6));
  EXPECT_EQ(r.best.shadow_volume, 0.0);
  EXPECT_EQ(r.best.risky_area, 0.0);
  // The stem's foot, a 48-gon of radius 3, rests on the plate.
  EXPECT_NEAR(r.best.contact_area, 0.5 * 48 * 9 * std::sin(2 * M_PI / 48), 1e-9);
  const Surface placed = apply_orientation(upside_down, r.rotation);
  EXPECT_NEAR(placed.V.col(2).maxCoeff(), 20.0, 1e-9);  // the dome's apex on top
}

TEST(Orientation, FlatCappedMushroomIsBestNeitherCapUpNorUpsideDown) {
  // mushroom()'s flat cap underside overhangs 10 mm above the plate when cap up (shadow about
  // 3000 mm³); upside down it balances on its shallow dome (about 410 mm³). Tilted over onto its
  // rim it needs less than either, and the search finds that from both starts.
  const Surface cap_up = test::mushroom();
  const Surface upside_down = test::transformed(cap_up, test::axis_angle({1, 0, 0}, M_PI), {0, 0, 16});
  const double cap_up_score = score_orientation(cap_up, Eigen::Vector3d::UnitZ()).score;
  const double upside_down_score = score_orientation(upside_down, Eigen::Vector3d::UnitZ()).score;
  EXPECT_GT(cap_up_score, 2500.0);
  EXPECT_LT(upside_down_score, 0.2 * cap_up_score);
  const OrientationResult from_up = optimize_orientation(cap_up), from_down = optimize_orientation(upside_down);
  EXPECT_LT(from_up.best.score, upside_down_score);
  // The best pose leans on the round rim, so the score is smooth there: the two refinements end
  // a few hundredths of a degree apart.
  EXPECT_NEAR(from_up.best.score, from_down.best.score, 1e-3 * from_up.best.score);
}

TEST(Orientation, LBracketEndsLyingOnItsLargestFace) {
  const test::LBracket p;
  std::mt19937_64 gen(8);
  for (int trial = 0; trial < 4; ++trial) {
    const Surface turned = test::transformed(test::l_bracket(p), test::random_rotation(gen), {7, -3, 11});
    const OrientationResult r = optimize_orientation(turned);
    EXPECT_EQ(r.best.shadow_volume, 0.0) << trial;
    EXPECT_NEAR(r.best.contact_area, p.base * p.width, 1e-6) << trial;
    // In the print pose the base lies flat: its underside on z = 0, the upright standing up.
    const Surface placed = apply_orientation(turned, r.rotation);
    EXPECT_NEAR(placed.V.col(2).maxCoeff(), p.upright, 1e-9) << trial;
    const Eigen::VectorXd z = sorted_heights(placed);
    EXPECT_NEAR(z(3), 0.0, 1e-9) << trial;  // the base's 4 underside corners
    EXPECT_GT(z(4), p.thickness - 1e-9) << trial;
  }
}

TEST(Orientation, RandomlyTurnedShapesEndInTheirNaturalBestPose) {
  std::mt19937_64 gen(5);
  // The default T rests equally well on its bar's top and on its side (both 500 mm², no overhang);
  // with a thicker bar the side wins, and the best pose is one up to symmetry.
  test::TShape thick_bar;
  thick_bar.bar_thickness = 8;
  for (const NamedShape& shape : {NamedShape{"T", test::t_shape(thick_bar)}, NamedShape{"arch", test::arch()},
                                  NamedShape{"L-bracket", test::l_bracket()},
                                  NamedShape{"printable mushroom", test::printable_mushroom()},
                                  NamedShape{"box", test::box({0, 0, 0}, {10, 20, 30})}}) {
    const OrientationResult natural = optimize_orientation(shape.surface);
    const Eigen::VectorXd natural_heights = sorted_heights(apply_orientation(shape.surface, natural.rotation));
    const double scale = face_areas(shape.surface).sum() * part_size(shape.surface);
    for (int trial = 0; trial < 3; ++trial) {
      const Surface turned = test::transformed(shape.surface, test::random_rotation(gen), {-4, 9, 2});
      const OrientationResult r = optimize_orientation(turned);
      SCOPED_TRACE(shape.name + " trial " + std::to_string(trial));
      EXPECT_LE(r.best.score, natural.as_given.score + 1e-9 * scale);  // no worse than as designed
      EXPECT_NEAR(r.best.score, natural.best.score, 1e-9 * scale);
      EXPECT_LT((sorted_heights(apply_orientation(turned, r.rotation)) - natural_heights).cwiseAbs().maxCoeff(),
                1e-6 * part_size(shape.surface));
    }
  }
}

TEST(Orientation, BoxStaysAsGivenAndATurnedBoxLandsOnItsLargestFace) {
  const Surface box = test::box({0, 0, 0}, {10, 20, 30});
  // Its largest faces are 20 x 30, at x = 0 and x = 10: lying on either, it stands 10 high.
  const OrientationResult r = optimize_orientation(box);
  EXPECT_NEAR(r.best.contact_area, 600.0, 1e-9);
  EXPECT_NEAR(std::abs(r.best.direction.x()), 1.0, 1e-12);
  std::mt19937_64 gen(2);
  const Surface turned = test::transformed(box, test::random_rotation(gen));
  const Surface placed = apply_orientation(turned, optimize_orientation(turned).rotation);
  EXPECT_NEAR(placed.V.col(2).maxCoeff(), 10.0, 1e-9);
  // A cube has six equal best faces: the tie goes to the pose as given.
  const OrientationResult cube = optimize_orientation(test::box({0, 0, 0}, {10, 10, 10}));
  EXPECT_EQ(cube.best.direction, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(cube.best.origin, "as given");
  EXPECT_TRUE(cube.rotation.isIdentity(0.0));
}

TEST(Orientation, ATieGoesToAFaceFlatOnThePlateNotToATiltWithinTheTolerance) {
  // A 2 x 40 x 60 plate with its largest face (40 x 60, at x = 0) turned 10° off face down. With a
  // plate tolerance of 0.5 mm every direction that tilts that face by less than about 0.5° still
  // rests it on the plate and scores exactly the same: no overhang, the same contact. With a dense
  // sphere, some of those directions lie nearer +Z than the face flat down and reach the exact
  // scoring; the search must still lay the face flat, not on one edge.
  const Surface plate = test::box({0, 0, 0}, {2, 40, 60});
  const Surface turned = test::transformed(plate, test::axis_angle({0, 1, 0}, -80.0 * M_PI / 180.0));
  OrientationOptions o;
  o.plate = PlateRule::within(0.5);
  o.sphere_candidates = 200000;
  o.support_model_candidates = 0;  // the score alone: the support model would see the tilt
  const OrientationResult r = optimize_orientation(turned, o);
  EXPECT_THAT(r.best.origin, ::testing::AnyOf("flat face down", "hull facet"));
  EXPECT_NEAR(r.best.contact_area, 2400.0, 1e-9);
  // Flat on its largest face the plate stands 2 high, four corners on the build plate.
  const Eigen::VectorXd z = sorted_heights(apply_orientation(turned, r.rotation));
  EXPECT_LT(z(3), 1e-9);
  EXPECT_NEAR(z(z.size() - 1), 2.0, 1e-9);
}

TEST(Orientation, SphereAndCubeAreDeterministicOnAnyThreadCount) {
  for (const Surface& s : {test::icosphere(4), test::transformed(test::box({0, 0, 0}, {10, 10, 10}), test::axis_angle({1, 2, 3}, 0.4))}) {
    OrientationOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const OrientationResult a = optimize_orientation(s, one), b = optimize_orientation(s, one),
                            c = optimize_orientation(s, two);
    for (const OrientationResult* other : {&b, &c}) {
      EXPECT_EQ(a.best.direction, other->best.direction);
      EXPECT_EQ(a.best.score, other->best.score);
      EXPECT_EQ(a.candidates, other->candidates);
      ASSERT_EQ(a.top.size(), other->top.size());
      for (size_t k = 0; k < a.top.size(); ++k) {
        EXPECT_EQ(a.top[k].direction, other->top[k].direction);
        EXPECT_EQ(a.top[k].score, other->top[k].score);
      }
    }
  }
}

TEST(Orientation, SphereScoresMatchTheSmoothSphereInEveryPose) {
  // A ball of radius r on its lowest point: the faces within 90° - alpha of straight down are
  // risky, at height r (1 - cos t), with footprint cos t:
  //   shadow = 2 pi r³ * integral over u = cos t from sin(alpha) to 1 of (1 - u) u du.
  // Every pose of the icosphere is that ball up to its tessellation (a few %).
  const double r = 10.0, s = std::sin(M_PI / 4);
  const double smooth = 2 * M_PI * r * r * r * ((0.5 - 1.0 / 3.0) - (s * s / 2 - s * s * s / 3));
  const OrientationResult result = optimize_orientation(test::icosphere(4, r));
  for (const OrientationCandidate* c : {&result.best, &result.as_given, &result.top.back()})
    EXPECT_NEAR(c->score, smooth, 0.05 * smooth) << c->origin;
}

TEST(Orientation, InsideOutMeshIsSearchedTurnedOver) {
  const Surface t = test::transformed(test::t_shape(), test::axis_angle({1, 1, 0}, 0.8));
  const OrientationResult right = optimize_orientation(t), turned = optimize_orientation(flipped(t));
  EXPECT_FALSE(right.inside_out);
  EXPECT_TRUE(turned.inside_out);
  EXPECT_EQ(right.best.direction, turned.best.direction);
  EXPECT_NEAR(right.best.score, turned.best.score, 1e-9 * std::abs(right.best.score));
}

TEST(Orientation, PrintPoseRestsOnThePlateAndIsRigid) {
  std::mt19937_64 gen(3);
  const Surface t = test::transformed(test::t_shape(), test::random_rotation(gen), {100, -50, 30});
  const OrientationResult r = optimize_orientation(t);
  EXPECT_TRUE((r.rotation * r.best.direction).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  EXPECT_NEAR((r.rotation.transpose() * r.rotation - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(r.rotation.determinant(), 1.0, 1e-12);
  const Surface placed = apply_orientation(t, r.rotation);
  EXPECT_EQ(placed.V.col(2).minCoeff(), 0.0);
  EXPECT_EQ(placed.F, t.F);
  for (Eigen::Index v = 1; v < t.V.rows(); ++v)
    EXPECT_NEAR((placed.V.row(v) - placed.V.row(0)).norm(), (t.V.row(v) - t.V.row(0)).norm(), 1e-9);
  // The placement turns the part in place: its centroid keeps x and y.
  EXPECT_TRUE(placed.V.colwise().mean().head<2>().isApprox(t.V.colwise().mean().head<2>(), 1e-12));
  // In the print pose, the pose as given is the best one.
  EXPECT_NEAR(score_orientation(placed, Eigen::Vector3d::UnitZ()).score, r.best.score, 1e-9 * std::abs(r.best.score) + 1e-9);
  EXPECT_TRUE(rotation_to_up(-Eigen::Vector3d::UnitZ()).isApprox(Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal())));
}

TEST(Orientation, SupportModelPicksTheLeastSupportOfTheBest) {
  // Step 5: of the poses the model judged in full (the list and the pose as given), the least
  // support wins, or a pose that stands by itself within 5% of it; no pose the rule admits needs
  // clearly less (beyond the model's noise, 1% + 1 mm³); each estimate is the model's own figure.
  for (const NamedShape& shape : shapes()) {
    SCOPED_TRACE(shape.name);
    const OrientationResult r = optimize_orientation(shape.surface, OrientationOptions{});
    ASSERT_FALSE(r.top.empty());
    EXPECT_EQ(r.best.direction, r.top.front().direction);
    SupportModelOptions m;
    m.print.direction = r.best.direction;
    ASSERT_TRUE(r.best.support_estimate.has_value());  // judged; the T lying down needs none
    const double best = r.best.support_estimate.value();
    ASSERT_GE(best, 0.0);
    EXPECT_NEAR(best, estimate_support(shape.surface, m).volume_mm3, 1e-9 * best);
    ASSERT_TRUE(r.as_given.support_estimate.has_value());  // the pose as given was judged too
    std::vector<const OrientationCandidate*> rivals = {&r.as_given};
    for (size_t k = 1; k < r.top.size(); ++k) rivals.push_back(&r.top[k]);
    double least = best;
    for (const OrientationCandidate* c : rivals) least = std::min(least, c->support_estimate.value());
    EXPECT_LE(best, least * 1.05 + 1.0);
    for (const OrientationCandidate* c : rivals) {
      if (c->stable || !r.best.stable) {
        EXPECT_GE(c->support_estimate.value() * 1.01 + 1.0, best) << c->origin;
      }
    }
  }
}

TEST(Orientation, ATieInSupportGoesToThePoseRestingMoreOnThePlate) {
  // A post standing on its end needs no support, and none lying down either: the support model
  // cannot tell them apart, and lying down it rests four times the area on the plate. (A cube,
  // alike on every face, stays as given: BoxStaysAsGivenAndATurnedBoxLandsOnItsLargestFace.)
  const Surface post = test::box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 10, 40));
  const OrientationResult r = optimize_orientation(post, OrientationOptions{});
  EXPECT_EQ(r.as_given.support_estimate.value(), 0.0);
  EXPECT_EQ(r.best.support_estimate.value(), 0.0);
  EXPECT_NEAR(r.best.contact_area, 400.0, 1e-9);
  EXPECT_NEAR(r.as_given.contact_area, 100.0, 1e-9);
  EXPECT_LT(std::abs(r.best.direction.z()), 1e-9);
}
