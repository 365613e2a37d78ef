// The nearest-item search of core/geometry/uniform_grid.h against a scan of every item: random segments
// (some long, crossing many cells) in grids of several shapes, queried near the items, far
// outside the grid and on whole-number points where items tie; the item found (ties to the lower
// index) and its distance, exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/uniform_grid.h"

using namespace slim;

namespace {

struct Segment {
  Eigen::Vector3d a, b;
};

double distance_to(const Segment& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d e = s.b - s.a;
  const double t = e.squaredNorm() > 0.0 ? std::clamp((p - s.a).dot(e) / e.squaredNorm(), 0.0, 1.0) : 0.0;
  return (s.a + t * e - p).norm();
}

}  // namespace

TEST(UniformGrid, TheNearestItemIsTheScansToTheBitAndTheIndex) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> in(0.0, 10.0), step(-0.6, 0.6), far(-40.0, 50.0);
  std::uniform_int_distribution<int> whole(0, 10);
  for (const Eigen::Vector3i& dims : {Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(8, 8, 8), Eigen::Vector3i(20, 3, 11)}) {
    std::vector<Segment> items;
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector3d a(in(gen), in(gen), in(gen));
      const Eigen::Vector3d b = i % 10 == 0 ? Eigen::Vector3d(in(gen), in(gen), in(gen)) : Eigen::Vector3d(a + Eigen::Vector3d(step(gen), step(gen), step(gen)));
      items.push_back({a, b});
    }
    items.push_back(items[5]);  // a repeated item: an exact tie at every point
    UniformGrid grid(Eigen::Vector3d::Zero(), Eigen::Vector3d(10.0, 10.0, 10.0).cwiseQuotient(dims.cast<double>()), dims);
    grid.fill(static_cast<int>(items.size()), [&](int i, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
      lo = items[static_cast<size_t>(i)].a.cwiseMin(items[static_cast<size_t>(i)].b);
      hi = items[static_cast<size_t>(i)].a.cwiseMax(items[static_cast<size_t>(i)].b);
    });
    for (int q = 0; q < 600; ++q) {
      const Eigen::Vector3d p = q < 200 ? Eigen::Vector3d(in(gen), in(gen), in(gen))
                                : q < 400 ? Eigen::Vector3d(far(gen), far(gen), far(gen))
                                          : Eigen::Vector3d(whole(gen), whole(gen), whole(gen));
      int expected = -1;
      double expected_distance = HUGE_VAL;
      for (int i = 0; i < static_cast<int>(items.size()); ++i) {
        const double d = distance_to(items[static_cast<size_t>(i)], p);
        if (d < expected_distance) expected = i, expected_distance = d;
      }
      double best = 0.0;
      const int found = grid.nearest(p, [&](int i) { return distance_to(items[static_cast<size_t>(i)], p); }, best);
      EXPECT_EQ(found, expected) << dims.transpose() << " | " << p.transpose();
      EXPECT_EQ(best, expected_distance) << dims.transpose() << " | " << p.transpose();
    }
  }
}
