// The overhang region's boundary and the direction to its nearest edge: known answers on the T,
// and the grid search against a scan of every segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "core/print/overhang.h"
#include "core/print/overhang_boundary.h"
#include "support/shapes.h"

using namespace slim;

namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

OverhangBoundary t_boundary(int refinement) {
  const Surface t = test::refined(test::t_shape(), refinement);
  return OverhangBoundary(t, analyse_overhang(t).risky);
}

double brute_force_nearest(const OverhangBoundary& b, const Eigen::Vector3d& p) {
  double best = HUGE_VAL;
  for (Eigen::Index i = 0; i < b.segment_count(); ++i) {
    const Eigen::Vector3d a = b.segment_start(i), ab = b.segment_end(i) - a;
    const double u = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + u * ab - p).norm());
  }
  return best;
}

}  // namespace

TEST(OverhangBoundary, TheTsBoundaryIsThePerimeterOfItsArmUndersides) {
  // Each arm's underside is a 20 x 10 rectangle at z = 20: perimeter 60, whatever the tessellation.
  for (int refinement : {0, 2, 4}) {
    const OverhangBoundary b = t_boundary(refinement);
    double length = 0.0;
    for (Eigen::Index i = 0; i < b.segment_count(); ++i) {
      length += (b.segment_end(i) - b.segment_start(i)).norm();
      EXPECT_NEAR(b.segment_start(i).z(), 20.0, 1e-12);
      EXPECT_NEAR(b.segment_end(i).z(), 20.0, 1e-12);
    }
    EXPECT_NEAR(length, 120.0, 1e-9) << "refinement " << refinement;
  }
}

TEST(OverhangBoundary, FlatOverhangsTurnTowardsTheirNearestEdge) {
  const OverhangBoundary b = t_boundary(3);
  struct Probe {
    Eigen::Vector3d point, expected;
  };
  const Probe probes[] = {
      {{15, 3, 20.5}, {0, 1, 0}},    // near the right arm's +y side
      {{15, -3.5, 20.5}, {0, -1, 0}},  // near its -y side
      {{23, 0.5, 20.5}, {1, 0, 0}},  // near its tip
      {{6, 0.5, 20.5}, {-1, 0, 0}},  // near the stem
      {{-22, 1, 21}, {-1, 0, 0}},    // near the left arm's tip
  };
  for (const Probe& p : probes)
    EXPECT_LT((b.toward_nearest(p.point, kUp) - p.expected).norm(), 1e-12) << p.point.transpose();
  // The direction is horizontal for any print direction: only its part across d counts.
  const Eigen::Vector3d tilted = Eigen::Vector3d(0.3, 0.1, 1).normalized();
  const Eigen::Vector3d w = b.toward_nearest({15, 3, 20.5}, tilted);
  EXPECT_NEAR(w.norm(), 1.0, 1e-12);
  EXPECT_NEAR(w.dot(tilted), 0.0, 1e-12);
}

TEST(OverhangBoundary, AnArchsFlatCrownTurnsTowardsItsCurvedSidesNotItsFrontAndBack) {
  // The arch's opening (radius 10 about (0, 8) in x-z, 10 deep in y) in 24 segments: its flat
  // region, the risky faces within 10 degrees of straight down, is the crown strip |x| < 1.3. Its
  // faces turn towards the curved overhang at the strip's sides (a pointed arch), where the
  // whole overhang's nearest edge would be the front or back (a keel across the opening).
  const Surface arch = test::arch();
  const OverhangReport r = analyse_overhang(arch);
  const Points n = face_normals(arch);
  std::vector<bool> flat(r.risky.size());
  for (size_t f = 0; f < flat.size(); ++f) flat[f] = r.risky[f] && n(static_cast<Eigen::Index>(f), 2) <= -std::cos(10 * M_PI / 180);
  ASSERT_EQ(std::count(flat.begin(), flat.end(), true), 4);  // two segments, two triangles each
  const Eigen::Vector3d crown(0.5, 3.5, 18.3);
  EXPECT_LT((OverhangBoundary(arch, flat).toward_nearest(crown, kUp) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_GT(OverhangBoundary(arch, r.risky).toward_nearest(crown, kUp).y(), 0.99);  // the front's arc
}

TEST(OverhangBoundary, StraightBelowAnEdgeThereIsNoHorizontalDirection) {
  const OverhangBoundary b = t_boundary(0);
  Eigen::Vector3d closest;
  EXPECT_NEAR(b.nearest({15, 5, 12}, closest), 8.0, 1e-12);  // right under the +y edge
  EXPECT_EQ(b.toward_nearest({15, 5, 12}, kUp), Eigen::Vector3d::Zero());
}

TEST(OverhangBoundary, GridSearchFindsWhatAScanOfEverySegmentFinds) {
  // A bumpy sphere with a random overhang region (many short segments), and the T (long ones),
  // queried inside and far outside their boxes.
  std::mt19937 gen(7);
  Surface sphere = test::icosphere(4);
  std::uniform_real_distribution<double> bump(-0.3, 0.3), coin(0.0, 1.0), far(-60.0, 60.0);
  for (Eigen::Index v = 0; v < sphere.V.rows(); ++v) sphere.V.row(v) *= 1.0 + 0.05 * bump(gen);
  std::vector<bool> random_region(static_cast<size_t>(sphere.F.rows()));
  for (size_t f = 0; f < random_region.size(); ++f) random_region[f] = coin(gen) < 0.3;
  const Surface t = test::t_shape();
  const OverhangBoundary cases[] = {OverhangBoundary(sphere, random_region), OverhangBoundary(t, analyse_overhang(t).risky)};
  for (const OverhangBoundary& b : cases) {
    ASSERT_GT(b.segment_count(), 0);
    for (int q = 0; q < 2000; ++q) {
      const double scale = q < 1000 ? 0.4 : 1.0;  // half near the boundary, half anywhere
      const Eigen::Vector3d p(scale * far(gen), scale * far(gen), 10 + scale * far(gen));
      Eigen::Vector3d closest;
      const double found = b.nearest(p, closest);
      EXPECT_EQ(found, brute_force_nearest(b, p)) << p.transpose();
      EXPECT_NEAR((closest - p).norm(), found, 1e-12);
    }
  }
}

TEST(OverhangBoundary, NoOverhangMeansNoBoundaryAndNoDirection) {
  const Surface cube = test::box({0, 0, 0}, {10, 10, 10});
  const OverhangBoundary b(cube, analyse_overhang(cube).risky);
  EXPECT_EQ(b.segment_count(), 0);
  Eigen::Vector3d closest;
  EXPECT_EQ(b.nearest({1, 2, 3}, closest), HUGE_VAL);
  EXPECT_EQ(b.toward_nearest({1, 2, 3}, kUp), Eigen::Vector3d::Zero());
  // Every face risky: a closed region has no edge either.
  EXPECT_EQ(OverhangBoundary(cube, std::vector<bool>(static_cast<size_t>(cube.F.rows()), true)).segment_count(), 0);
}

TEST(OverhangBoundary, RefusesFlagsThatDoNotMatchTheFaces) {
  const Surface cube = test::box({0, 0, 0}, {10, 10, 10});
  EXPECT_THROW(OverhangBoundary(cube, std::vector<bool>(3, true)), std::invalid_argument);
}

TEST(OverhangBoundary, ExtremeCoordinatesStayDefined) {
  // The robustness catalogue's scales (1e-3 and 1e6) keep their exact answer. Far beyond them,
  // squared distances under- or overflow and a T so large that its extent overflows a double
  // leaves the grid unit cells: the answers are then only defined, never undefined behaviour (the
  // sanitizer stage runs this too).
  const std::vector<bool> arms = analyse_overhang(test::t_shape()).risky;  // normals would under/overflow
  for (double scale : {1e-3, 1e6, 1e-200, 1e200, 5e306}) {
    const Surface t = test::transformed(test::t_shape(), scale * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    const OverhangBoundary b(t, arms);
    EXPECT_GT(b.segment_count(), 0) << scale;
    const Eigen::Vector3d w = b.toward_nearest(scale * Eigen::Vector3d(15, 3, 20.5), kUp);
    EXPECT_TRUE(w.allFinite()) << scale;
    if (scale == 1e-3 || scale == 1e6) {
      EXPECT_LT((w - Eigen::Vector3d(0, 1, 0)).norm(), 1e-9) << scale;
    }
  }
}

// The boundary is every edge along which exactly one face of the region runs, in the order of
// (lower vertex, higher vertex): against a count over every face of the mesh, for random regions of
// a closed ball and of an open half ball (whose rim edges have one face only).
TEST(OverhangBoundary, TheSegmentsAreTheEdgesOneRegionFaceRunsAlong) {
  std::mt19937 gen(7);
  for (const Surface& s : {test::icosphere(3), test::open_hemisphere(3)}) {
    for (double share : {0.1, 0.5, 0.9}) {
      std::bernoulli_distribution in(share);
      std::vector<bool> region(static_cast<size_t>(s.F.rows()));
      for (size_t f = 0; f < region.size(); ++f) region[f] = in(gen);
      std::map<std::pair<int, int>, int> uses;
      for (Eigen::Index f = 0; f < s.F.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
          const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
          uses[{std::min(u, v), std::max(u, v)}] += region[static_cast<size_t>(f)] ? 1 : 0;
        }
      std::vector<std::pair<int, int>> expected;
      for (const auto& [edge, count] : uses)
        if (count == 1) expected.push_back(edge);
      const OverhangBoundary boundary(s, region);
      ASSERT_EQ(boundary.segment_count(), static_cast<Eigen::Index>(expected.size())) << share;
      ASSERT_GT(expected.size(), 0u);
      for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(boundary.segment_start(static_cast<Eigen::Index>(i)), s.V.row(expected[i].first).transpose()) << i;
        EXPECT_EQ(boundary.segment_end(static_cast<Eigen::Index>(i)), s.V.row(expected[i].second).transpose()) << i;
      }
    }
  }
}
