// Volume change and crease share (core/geometry/shape_metrics.h): invariants under rigid motions and
// scales, and folds whose share of creased edge length follows from the tessellation by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "core/geometry/shape_metrics.h"
#include "core/platform/parallel_for.h"
#include "support/shapes.h"

using namespace slim;

namespace {

// An open square sheet [0,1]^2 at z = 0 of n x n cells, each split along one diagonal. Interior
// edges: 2 n (n - 1) axis-parallel ones of length 1/n, and n^2 diagonals of length sqrt(2)/n.
Surface sheet(int n) {
  Surface s;
  s.V.resize((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.V.row(j * (n + 1) + i) << double(i) / n, double(j) / n, 0.0;
  s.F.resize(2 * n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      s.F.row(2 * (j * n + i)) << a, b, d;
      s.F.row(2 * (j * n + i) + 1) << a, d, c;
    }
  return s;
}

// The half x > 1/2 of a sheet turned about the line x = 1/2, z = 0 by `degrees` (positive: the
// far half rises, so the sheet bends towards its normal +Z: a valley, concave).
Surface folded(const Surface& s, double degrees) {
  Surface out = s;
  const Eigen::Matrix3d R = test::axis_angle(Eigen::Vector3d::UnitY(), -degrees * M_PI / 180.0);
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
    if (s.V(v, 0) <= 0.5) continue;
    const Eigen::Vector3d p = s.V.row(v).transpose() - Eigen::Vector3d(0.5, 0, 0);
    out.V.row(v) = (R * p + Eigen::Vector3d(0.5, 0, 0)).transpose();
  }
  return out;
}

// The fold line's n edges against all interior edge length (see sheet()).
double fold_share_pct(int n) { return 100.0 / (2.0 * (n - 1) + n * std::sqrt(2.0)); }

}  // namespace

TEST(ShapeMetrics, ACubeHasTwelveConvexRightAnglesAndSixFlatDiagonals) {
  const std::vector<DihedralEdge> edges = dihedral_edges(test::box({0, 0, 0}, {1, 2, 3}));
  ASSERT_EQ(edges.size(), 18u);
  int right = 0, flat = 0;
  for (const DihedralEdge& e : edges) {
    if (std::abs(e.angle_deg - 90.0) < 1e-9) ++right;
    if (std::abs(e.angle_deg) < 1e-9) ++flat;
  }
  EXPECT_EQ(right, 12);
  EXPECT_EQ(flat, 6);
}

TEST(ShapeMetrics, ARigidMotionChangesNothing) {
  const Surface in = test::icosphere(3, 10.0);
  const Eigen::Matrix3d R = test::axis_angle(Eigen::Vector3d(1, 2, 3).normalized(), 0.7);
  const ShapeChange c = shape_change(in, test::transformed(in, R, Eigen::Vector3d(40, -7, 3)));
  EXPECT_TRUE(c.volume_defined);
  EXPECT_NEAR(c.volume_change_pct, 0.0, 1e-9);
  EXPECT_EQ(c.crease_share_pct, 0.0);
  EXPECT_LT(c.max_crease_deg, 1e-6);
  EXPECT_EQ(c.interior_edges, 3 * in.F.rows() / 2);  // a closed surface: every edge is interior
}

TEST(ShapeMetrics, AUniformScaleChangesTheVolumeByItsCube) {
  const Surface in = test::t_shape();
  for (double s : {0.5, 1.3, 2.0}) {
    const ShapeChange c = shape_change(in, test::transformed(in, s * Eigen::Matrix3d::Identity()));
    EXPECT_NEAR(c.volume_change_pct, 100.0 * (s * s * s - 1.0), 1e-9) << s;
    EXPECT_NEAR(c.volume_input, signed_volume(in), 1e-9);
    EXPECT_EQ(c.crease_share_pct, 0.0) << s;
    EXPECT_LT(c.max_crease_deg, 1e-6) << s;
  }
}

TEST(ShapeMetrics, AFoldCreasesExactlyTheFoldLine) {
  for (int n : {4, 10, 20}) {
    const Surface in = sheet(n);
    for (double degrees : {30.0, -30.0, 90.0}) {
      const ShapeChange c = shape_change(in, folded(in, degrees));
      EXPECT_NEAR(c.crease_share_pct, fold_share_pct(n), 1e-9) << n << " " << degrees;
      EXPECT_NEAR(c.max_crease_deg, std::abs(degrees), 1e-9);
      // The fold holds more than 1% of the length, so the 99th percentile is the fold itself.
      EXPECT_NEAR(c.crease_p99_deg, std::abs(degrees), 1e-9);
      EXPECT_FALSE(c.volume_defined);  // an open sheet encloses nothing
    }
  }
}

TEST(ShapeMetrics, TheFoldsSignTellsAValleyFromARidge) {
  const Surface in = sheet(4);
  for (const DihedralEdge& e : dihedral_edges(folded(in, 30.0))) {
    if (std::abs(e.angle_deg) > 1e-9) {
      EXPECT_NEAR(e.angle_deg, -30.0, 1e-9);  // bent towards +Z: concave
    }
  }
  // A ridge folded into a valley of the same angle changes by twice the angle.
  const ShapeChange c = shape_change(folded(in, -20.0), folded(in, 20.0));
  EXPECT_NEAR(c.max_crease_deg, 40.0, 1e-9);
  EXPECT_NEAR(c.crease_share_pct, fold_share_pct(4), 1e-9);
}

TEST(ShapeMetrics, ABendBelowTheThresholdIsNoCrease) {
  const Surface in = sheet(10);
  const ShapeChange c = shape_change(in, folded(in, 8.0));
  EXPECT_EQ(c.crease_share_pct, 0.0);
  EXPECT_NEAR(c.max_crease_deg, 8.0, 1e-9);
  ShapeChangeOptions strict;
  strict.crease_threshold_deg = 5.0;
  EXPECT_NEAR(shape_change(in, folded(in, 8.0), strict).crease_share_pct, fold_share_pct(10), 1e-9);
}

TEST(ShapeMetrics, ARareCreaseStaysOutOfTheNinetyNinthPercentile) {
  // 100 cells: the fold is 0.29% of the edge length, under the 1% the percentile leaves out.
  const Surface in = sheet(100);
  const ShapeChange c = shape_change(in, folded(in, 45.0));
  EXPECT_NEAR(c.crease_share_pct, fold_share_pct(100), 1e-9);
  EXPECT_LT(fold_share_pct(100), 1.0);
  EXPECT_LT(c.crease_p99_deg, 1e-9);
  EXPECT_NEAR(c.max_crease_deg, 45.0, 1e-9);
}

TEST(ShapeMetrics, OpenNonManifoldAndDegenerateEdgesAreNotMeasured) {
  // Two cubes sharing an edge: that edge has four faces and is left out; every other edge is
  // interior (the cubes are closed).
  const Surface two = test::two_cubes_sharing_edge(1.0);
  EXPECT_EQ(dihedral_edges(two).size(), 2u * 18u - 2u);  // 35 distinct edges, one of them non-manifold
  // A single triangle has no interior edge.
  const ShapeChange c = shape_change(test::triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}),
                                     test::triangle({0, 0, 0}, {2, 0, 0}, {0, 1, 0}));
  EXPECT_EQ(c.interior_edges, 0);
  EXPECT_EQ(c.crease_share_pct, 0.0);
}

TEST(ShapeMetrics, DifferentMeshesAreRefused) {
  const Surface a = test::icosphere(1), b = test::icosphere(2);
  EXPECT_THROW(shape_change(a, b), std::invalid_argument);
  Surface reordered = a;
  reordered.F.row(0) = a.F.row(0).reverse();
  EXPECT_THROW(shape_change(a, reordered), std::invalid_argument);
  ShapeChangeOptions bad;
  bad.crease_threshold_deg = -1;
  EXPECT_THROW(shape_change(a, a, bad), std::invalid_argument);
}

// The optimizer measures every iterate with one meter: each measure is what the fold's geometry
// says, whatever was measured before (the meter keeps only the input).
TEST(ShapeMetrics, OneCreaseMeterMeasuresManyResultsAsTheyAre) {
  const int n = 10;
  const Surface in = sheet(n);
  const CreaseMeter meter(in);
  for (double degrees : {30.0, 5.0, -90.0, 0.0, 30.0}) {
    const Surface out = folded(in, degrees);
    ShapeChange c;
    meter.measure(out.V, c);
    const double expected = std::abs(degrees) > 10.0 ? fold_share_pct(n) : 0.0;
    EXPECT_NEAR(c.crease_share_pct, expected, 1e-9) << degrees;
    EXPECT_NEAR(meter.share_pct(out.V), expected, 1e-9) << degrees;
    EXPECT_NEAR(c.max_crease_deg, std::abs(degrees), 1e-9) << degrees;
    EXPECT_EQ(c.interior_edges, 2 * n * (n - 1) + n * n);
  }
  // A ball bent at random: the share without the angles is the share with them.
  const Surface ball = test::icosphere(3);
  const CreaseMeter ball_meter(ball);
  for (unsigned seed : {1u, 2u, 3u}) {
    Surface bent = ball;
    bent.V += 0.4 * Points::Random(ball.V.rows(), 3) * seed;
    ShapeChange c;
    ball_meter.measure(bent.V, c);
    EXPECT_GT(c.crease_share_pct, 1.0) << seed;
    EXPECT_NEAR(ball_meter.share_pct(bent.V), c.crease_share_pct, 1e-9) << seed;
    EXPECT_NEAR(c.crease_share_pct, shape_change(ball, bent).crease_share_pct, 1e-12) << seed;
  }
  // A result face squashed to no area drops its three edges from the measure.
  Surface squashed = in;
  squashed.V.row(in.F(0, 1)) = squashed.V.row(in.F(0, 0));
  ShapeChange c;
  meter.measure(squashed.V, c);
  EXPECT_LT(c.interior_edges, 2 * n * (n - 1) + n * n);
  EXPECT_NEAR(meter.share_pct(squashed.V), c.crease_share_pct, 1e-12);
  EXPECT_THROW(meter.measure(sheet(n + 1).V, c), std::invalid_argument);
}

// share_pct runs its faces and edges on the threads: on a ball large enough for them (122,880
// edges), bent at random, it gives measure()'s share on one thread and on two, the same bits on
// both, call after call with one meter (its buffers reused).
TEST(ShapeMetrics, TheShareOfALargeSurfaceIsTheSameOnAnyThreadCount) {
  const Surface ball = test::icosphere(6);
  const CreaseMeter meter(ball);
  for (unsigned seed : {1u, 2u}) {
    Surface bent = ball;
    std::srand(seed);
    bent.V += 0.05 * Points::Random(ball.V.rows(), 3);
    ShapeChange c;
    meter.measure(bent.V, c);
    ASSERT_GT(c.crease_share_pct, 1.0) << seed;
    ASSERT_LT(c.crease_share_pct, 99.0) << seed;
    std::vector<double> shares;
    for (int threads : {1, 2, 1}) {
      const ThreadScope scope(threads);
      shares.push_back(meter.share_pct(bent.V));
    }
    EXPECT_NEAR(shares[0], c.crease_share_pct, 1e-9) << seed;
    EXPECT_EQ(shares[0], shares[1]) << seed;
    EXPECT_EQ(shares[0], shares[2]) << seed;
  }
}
