// The overhangs the optimizer turns: ranked by the support column under them, kept until they
// carry the share asked for.
#include <gtest/gtest.h>

#include <vector>

#include "core/optimizer/costly_overhangs.h"
#include "core/optimizer/slimming.h"
#include "core/print/overhang.h"
#include "support/shapes.h"

using namespace slim;

namespace {

// A block on the plate and two boxes of the same size above it at z 8: the one over the block
// needs a 4 mm column, the one beyond it an 8 mm column: a third and two thirds of the cost, each
// in two triangles.
Surface ledge() {
  return test::merge(test::box({0, 0, 0}, {10, 10, 4}),
                     test::merge(test::box({0, 0, 8}, {10, 10, 12}), test::box({10, 0, 8}, {20, 10, 12})));
}

double centroid_x(const Surface& s, Eigen::Index f) {
  return (s.V(s.F(f, 0), 0) + s.V(s.F(f, 1), 0) + s.V(s.F(f, 2), 0)) / 3.0;
}

// Counts the kept faces over the block (x < 10) and beyond it.
std::pair<int, int> kept(const Surface& s, const std::vector<bool>& costly) {
  std::pair<int, int> n{0, 0};
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (costly[static_cast<size_t>(f)]) (centroid_x(s, f) < 10.0 ? n.first : n.second) += 1;
  return n;
}

}  // namespace

TEST(CostlyOverhangs, TheTallColumnsComeFirstAndTheShortOnesLast) {
  const Surface s = ledge();
  const OverhangReport r = analyse_overhang(s);
  ASSERT_EQ(r.risky_count, 4);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  EXPECT_EQ(kept(s, costly_overhangs(s, r, up, 0.6)), std::make_pair(0, 2));  // 2/3 of the cost
  EXPECT_EQ(kept(s, costly_overhangs(s, r, up, 0.8)), std::make_pair(1, 2));  // 5/6
  EXPECT_EQ(kept(s, costly_overhangs(s, r, up, 0.9)), std::make_pair(2, 2));
  EXPECT_EQ(costly_overhangs(s, r, up, 1.0), r.risky);
}

TEST(CostlyOverhangs, TheKeptFacesAreRiskyAndGrowWithTheShare) {
  const Surface s = test::sample_bunny();
  const OverhangReport r = analyse_overhang(s);
  std::vector<bool> fewer(r.risky.size(), false);
  for (const double share : {0.3, 0.8, 0.95}) {
    const std::vector<bool> costly = costly_overhangs(s, r, Eigen::Vector3d::UnitZ(), share);
    int count = 0;
    for (size_t f = 0; f < costly.size(); ++f) {
      EXPECT_TRUE(!costly[f] || r.risky[f]);
      EXPECT_TRUE(!fewer[f] || costly[f]) << "a larger share keeps what a smaller one kept";
      count += costly[f];
    }
    EXPECT_GT(count, 0);
    EXPECT_LT(count, r.risky_count) << "share " << share;
    fewer = costly;
  }
}

// The slimming spends its turns on the costly overhangs: with a share of 0.5 the vertices that
// only cheap overhangs hold move less than when every overhang is turned, while the costly
// ones still move and the support still falls.
TEST(CostlyOverhangs, TheSlimmingLeavesTheCheapOverhangsAlone) {
  const Surface& bunny = test::sample_bunny();
  const OverhangReport r = analyse_overhang(bunny);
  const std::vector<bool> costly = costly_overhangs(bunny, r, Eigen::Vector3d::UnitZ(), 0.5);
  std::vector<int> role(static_cast<size_t>(bunny.V.rows()), 0);  // 1: cheap only, 2: costly
  for (Eigen::Index f = 0; f < bunny.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      int& v = role[static_cast<size_t>(bunny.F(f, j))];
      if (costly[static_cast<size_t>(f)]) v = 2;
      else if (r.risky[static_cast<size_t>(f)] && v == 0) v = 1;
    }
  auto mean_moved = [&](const SlimmingResult& s, int which) {
    double sum = 0.0;
    int n = 0;
    for (Eigen::Index v = 0; v < bunny.V.rows(); ++v)
      if (role[static_cast<size_t>(v)] == which) sum += (s.surface.V.row(v) - bunny.V.row(v)).norm(), ++n;
    return sum / n;
  };
  SlimmingOptions o;
  o.ladder.multiples.clear();
  const SlimmingResult all = slim_supports(bunny, o);
  o.coherence.costly_share = 0.5;
  const SlimmingResult focused = slim_supports(bunny, o);
  ASSERT_GT(all.iterations, 0) << all.stop_reason;
  ASSERT_GT(focused.iterations, 0) << focused.stop_reason;
  EXPECT_LT(mean_moved(focused, 1), 0.7 * mean_moved(all, 1));
  EXPECT_GT(mean_moved(focused, 2), mean_moved(focused, 1));
  EXPECT_LT(focused.support_after_mm3.value(), focused.support_before_mm3.value());
}
