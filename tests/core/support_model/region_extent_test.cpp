// How far each overhang region reaches up and down from its vertices, and the part of a feature
// the slicer sees (core/support_model/region_extent.h): the extents against a brute-force walk over the region,
// the heights shown against the slice-to-slice geometry worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/geometry/face_adjacency.h"
#include "core/support_model/region_extent.h"
#include "support/creatures.h"
#include "support/shapes.h"

namespace slim {
namespace {

const double kMargin = 0.2 / std::tan(46.0 * M_PI / 180.0);  // layer / tan(46°), PrusaSlicer's 45° + 1°

std::vector<char> looking_down_past(const Surface& s, double slope_deg) {
  std::vector<char> in(static_cast<size_t>(s.F.rows()), 0);
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d n = face_cross(s.V, s.F, f).normalized();
    in[f] = -n.z() > std::cos(slope_deg * M_PI / 180.0);
  }
  return in;
}

// The steepest face around v outside the regions that looks down and rises (up) or falls from v:
// its horizontal run per height.
double wall_run(const Surface& s, const FaceAdjacency& adj, const std::vector<char>& in, int v, bool up) {
  double run = 0.0;
  for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) {
    const Eigen::Vector3d n = face_cross(s.V, s.F, *f);
    double rise = 0.0;
    for (int u : adj.face(*f)) rise += s.V(u, 2) - s.V(v, 2);
    if (!in[*f] && n.z() < 0 && n.head<2>().norm() > 0 && (up ? rise > 0 : rise < 0)) run = std::max(run, -n.z() / n.head<2>().norm());
  }
  return run;
}

// Every vertex reached from start by steps along region faces' edges that go up (down): the
// highest (lowest) z among them, and the wall runs at the vertices at that z.
std::pair<double, std::vector<double>> walk(const Surface& s, const FaceAdjacency& adj, const std::vector<char>& in, int start,
                                            bool up) {
  std::vector<char> seen(static_cast<size_t>(s.V.rows()), 0);
  std::vector<int> stack{start}, reached;
  seen[start] = 1;
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    reached.push_back(v);
    for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) {
      if (!in[*f]) continue;
      for (int u : adj.face(*f))
        if (!seen[u] && (up ? s.V(u, 2) > s.V(v, 2) : s.V(u, 2) < s.V(v, 2))) seen[u] = 1, stack.push_back(u);
    }
  }
  double z = up ? -INFINITY : INFINITY;
  for (int v : reached) z = up ? std::max(z, s.V(v, 2)) : std::min(z, s.V(v, 2));
  std::vector<double> runs;
  for (int v : reached)
    if (s.V(v, 2) == z) runs.push_back(wall_run(s, adj, in, v, up));
  return {z, runs};
}

TEST(RegionExtent, EqualsABruteForceWalkOverTheRegions) {
  const Surface s = test::creature("long_neck", 1.6);
  const FaceAdjacency adj(s);
  const std::vector<char> in = looking_down_past(s, 46.0);
  const std::vector<RegionExtent> got = region_extents(s, adj, in);
  int regional = 0;
  for (int v = 0; v < s.V.rows(); ++v) {
    bool any = false;
    for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) any = any || in[*f];
    if (!any) {
      EXPECT_EQ(got[v].top, -INFINITY);
      EXPECT_EQ(got[v].bottom, INFINITY);
      continue;
    }
    ++regional;
    for (bool up : {true, false}) {
      const auto [z, runs] = walk(s, adj, in, v, up);
      EXPECT_EQ(up ? got[v].top : got[v].bottom, z) << v;
      const double run = up ? got[v].run_above : got[v].run_below;
      EXPECT_TRUE(std::find(runs.begin(), runs.end(), run) != runs.end()) << v << " " << run;
    }
  }
  EXPECT_GT(regional, 100);
}

TEST(RegionExtent, TheWallRunIsTheSteepestFaceLookingDownFromTheRegionsEdge) {
  // A cone flaring out from r = 3 at the plate to 3.6 at z = 0.6 (a run of 1 per height), then a
  // face to r = 3.7 at z = 1.6 (a run of 0.1: steeper than the threshold, no overhang), then a
  // wall. The flare's vertices reach up to 0.6 and see the 0.1 run above; down to the plate, with
  // the level bottom (in the region) below them and nothing steeper. Steps go strictly up or down.
  const Surface s = test::revolve({{0, 0}, {3, 0}, {3.6, 0.6}, {3.7, 1.6}, {3.7, 5}, {0, 5}}, 32);
  const FaceAdjacency adj(s);
  const std::vector<char> in = looking_down_past(s, 46.0);
  const std::vector<RegionExtent> e = region_extents(s, adj, in);
  for (int v = 0; v < s.V.rows(); ++v) {
    const double z = s.V(v, 2);
    if (z > 0.7) {
      EXPECT_EQ(e[v].top, -INFINITY) << z;  // above the region
      continue;
    }
    if (s.V.row(v).head<2>().norm() == 0) {  // the bottom's centre: no step from it goes up
      EXPECT_EQ(e[v].top, 0.0);
      continue;
    }
    EXPECT_NEAR(e[v].top, 0.6, 1e-12);
    EXPECT_NEAR(e[v].run_above, 0.1 / std::cos(M_PI / 32), 0.01);  // the facets' own slope
    EXPECT_EQ(e[v].bottom, 0.0);
    EXPECT_EQ(e[v].run_below, 0.0);
  }
}

TEST(RegionExtent, AFeatureShowsInItsTopAndBottomLayersOnlyWhereTheSurfaceReachesTheMargin) {
  const SlicePlanes planes;  // slices at 0.1, 0.3, 0.5, 0.7 mm: layer k between 0.2k - 0.1 and 0.2k + 0.1
  auto extent = [](double bottom, double top, double below, double above) {
    RegionExtent e;
    e.bottom = bottom, e.top = top, e.run_below = below, e.run_above = above;
    return e;
  };
  // A flare from the plate to z = 0.32 at a run of 1.09, a wall above: 0.02 × 1.09 past the slice at
  // 0.3 in layer 2, far short of the margin: shown up to that slice only.
  ShownHeights h = shown_heights(0.0, 0.32, 1.09, extent(0.0, 0.32, 0.0, 0.0), planes, kMargin);
  EXPECT_NEAR(h.high, 0.3, 1e-5);
  EXPECT_EQ(h.low, -INFINITY);  // layers 0 and 1: their contacts would lie under the first layer
  // The same flare to 0.48: 0.18 × 1.09 = 0.196 past the slice, just over the margin: all of it.
  h = shown_heights(0.0, 0.48, 1.09, extent(0.0, 0.48, 0.0, 0.0), planes, kMargin);
  EXPECT_EQ(h.high, INFINITY);
  // To 0.4 under a face with a run of 0.9 (steeper than 46°): 0.1 × 1.09 + 0.1 × 0.9 = 0.199.
  h = shown_heights(0.0, 0.4, 1.09, extent(0.0, 0.4, 0.0, 0.9), planes, kMargin);
  EXPECT_EQ(h.high, INFINITY);
  // A face from 0.45 to 0.6 over a wall, alone in its region, at a run of 1.67: 0.05 × 1.67 past
  // the slice at 0.3 in layer 2, 0.1 × 1.67 past the slice at 0.5 in layer 3: shown in neither.
  h = shown_heights(0.45, 0.6, 1.67, extent(0.45, 0.6, 0.0, 0.0), planes, kMargin);
  EXPECT_NEAR(h.low, 0.5, 1e-5);
  EXPECT_NEAR(h.high, 0.5, 1e-5);
  // Its region going on below and above it: every layer shown.
  h = shown_heights(0.45, 0.6, 1.67, extent(0.1, 2.0, 0.0, 0.0), planes, kMargin);
  EXPECT_EQ(h.low, -INFINITY);
  EXPECT_EQ(h.high, INFINITY);
  // A level face appears all at once.
  h = shown_heights(0.45, 0.45, INFINITY, extent(0.45, 0.45, 0.0, 0.0), planes, kMargin);
  EXPECT_EQ(h.low, -INFINITY);
  EXPECT_EQ(h.high, INFINITY);
}

}  // namespace
}  // namespace slim
