// The synthetic creatures (tests/support/creatures.h): closed, outward, standing on the plate,
// and overhanging the way figurines do: a rounded underside that bends gradually, not a flat
// ceiling like a T's arms.
#include <gtest/gtest.h>

#include <cmath>

#include "core/print/overhang.h"
#include "support/creatures.h"

using namespace slim;

#ifdef SLIM_TESTS_HAVE_VCG

TEST(Creatures, AreClosedOutwardAndStandOnThePlate) {
  for (const std::string& name : test::creature_names()) {
    const Surface s = test::creature(name);
    SCOPED_TRACE(name);
    ASSERT_GT(s.F.rows(), 5000);
    const EdgeTopology e = edge_topology(s);
    EXPECT_EQ(e.open_edges, 0) << e.first_open;
    EXPECT_EQ(e.nonmanifold_edges, 0) << e.first_nonmanifold;
    EXPECT_EQ(e.flipped_edges, 0) << e.first_flipped;
    EXPECT_GT(signed_volume(s), 1000.0);
    EXPECT_EQ(s.V.col(2).minCoeff(), 0.0);
    const Eigen::Vector3d size = s.V.colwise().maxCoeff() - s.V.colwise().minCoeff();
    EXPECT_GT(size.maxCoeff(), 45.0);
    EXPECT_LT(size.maxCoeff(), 80.0);
    const OverhangReport r = analyse_overhang(s);
    EXPECT_GT(r.plate_count, 0);  // flat feet on the plate
  }
}

TEST(Creatures, OverhangLikeFigurinesNotLikeAT) {
  for (const std::string& name : test::creature_names()) {
    const Surface s = test::creature(name);
    SCOPED_TRACE(name);
    const OverhangReport r = analyse_overhang(s);
    const Points n = face_normals(s);
    const Eigen::VectorXd a = face_areas(s);
    // A rounded underside: the risky area spreads over normals from straight down to the 45°
    // threshold; little of it faces within 10° of straight down (a T's arms: all of it).
    double risky = 0, flat = 0, steep = 0;
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
      if (!r.risky[static_cast<size_t>(f)]) continue;
      risky += a(f);
      if (-n(f, 2) > std::cos(10.0 * M_PI / 180.0)) flat += a(f);
      if (-n(f, 2) < std::cos(30.0 * M_PI / 180.0)) steep += a(f);
    }
    EXPECT_GT(r.risky_share(), 0.04);
    EXPECT_LT(flat, 0.5 * risky);
    EXPECT_GT(steep, 0.2 * risky);
  }
}

TEST(Creatures, RepeatAndRefuseBadArguments) {
  const Surface a = test::creature("upright", 1.5), b = test::creature("upright", 1.5);
  EXPECT_EQ(a.V, b.V);
  EXPECT_EQ(a.F, b.F);
  EXPECT_GT(test::creature("upright", 0.8).F.rows(), 2 * a.F.rows());  // finer cells, more faces
  EXPECT_THROW(test::creature("unicorn"), std::invalid_argument);
  EXPECT_THROW(test::creature("upright", 0.0), std::invalid_argument);
}

#endif  // SLIM_TESTS_HAVE_VCG
