// The features the support model hands its sweep as contacts (core/support_model/overhang_features.h): the rules
// checked against the layer-by-layer geometry worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "core/geometry/face_adjacency.h"
#include "core/support_model/overhang_features.h"
#include "support/shapes.h"

namespace slim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The (pixel, layer) pairs overhang_features() marks on s over the grid g.
std::set<std::pair<int, int>> marks(const Surface& s, const PixelGrid& g, const OverhangRule& rule = {}) {
  std::set<std::pair<int, int>> out;
  for (const PixelOverhang& o : overhang_features(s, FaceAdjacency(s), g, rule))
    for (int k = o.layer_low; k <= o.layer_high; ++k) out.insert({o.pixel, k});
  return out;
}

// A tunnel 10 mm wide through a block (along y, 10 mm long), standing on the plate: walls up to
// z = 6, then a 50-degree face (steeper than the 46-degree threshold) up to the edge at x = -e,
// z = z_edge, then a 35-degree face (an overhang) to the apex on x = 0; mirrored at x > 0.
Surface tunnel(double z_edge) {
  const double e = 5.0 - (z_edge - 6.0) / std::tan(50.0 * kDeg), apex = z_edge + e * std::tan(35.0 * kDeg);
  return test::prism_xz({{-10, 0}, {-5, 0}, {-5, 6}, {-e, z_edge}, {0, apex}, {e, z_edge}, {5, 6}, {5, 0}, {10, 0}, {10, 16}, {-10, 16}},
                        -5.0, 5.0);
}

// The layers marked over the pixels of column i (any row), by overhang_features() on the tunnel
// with 0.25 mm pixels whose column 20 begins 0.05 mm left of the edge (x = -e - 0.05).
std::set<int> layers_in_column(double z_edge, int i) {
  const Surface s = tunnel(z_edge);
  const double e = 5.0 - (z_edge - 6.0) / std::tan(50.0 * kDeg);
  PixelGrid g;
  g.pixel = 0.25;
  g.x0 = -e - 0.05 - 20 * g.pixel;
  g.y0 = -6.0;
  g.nx = g.ny = 96;
  std::set<int> layers;
  for (const auto& [pixel, k] : marks(s, g))
    if (pixel % g.nx == i) layers.insert(k);
  return layers;
}

TEST(OverhangFeatures, AnOverhangsEdgeReachesOverTheSteeperFaceBelowInItsOwnLayer) {
  // Layers of 0.2 mm: layer k spans the slices at 0.2 + (k - 1.5) 0.2 and 0.2 + (k - 0.5) 0.2 mm.
  // With the edge at z = 8.6, between the slices 8.5 and 8.7 of layer 43, the slicer's overhang in
  // layer 43 starts at the outline of the slice at 8.5, on the 50-degree face 0.1 / tan 50 =
  // 0.084 mm beyond the edge: past column 20's left side by 0.034 mm. Column 19 carries layer 43
  // and nothing else (the steeper face is no overhang in its other layers); column 18, beyond that
  // strip, nothing.
  EXPECT_EQ(layers_in_column(8.6, 19), std::set<int>{43});
  EXPECT_TRUE(layers_in_column(8.6, 18).empty());
  EXPECT_FALSE(layers_in_column(8.6, 20).empty());  // the overhanging face's own pixels
  // The edge at z = 8.52, just above the slice at 8.5: the strip is 0.02 / tan 50 = 0.017 mm wide
  // and stays in column 20.
  EXPECT_TRUE(layers_in_column(8.52, 19).empty());
  EXPECT_FALSE(layers_in_column(8.52, 20).empty());
}

// A tunnel whose ceiling is the tunnel() above turned over: walls to z = 6, a 35-degree overhang up
// to the edge at x = -e, then a 50-degree face (steeper than the threshold) up to the apex, so the
// steeper face lies above the edge. Sheared by z += 0.1 (y + 5), so the edge rises from z = 8.1 at
// y = -5 to 9.1 at y = 5 and the region's top is far from the layers looked at.
Surface rising_ceiling() {
  const double z_edge = 8.1, e = 5.0 - (z_edge - 6.0) / std::tan(35.0 * kDeg), apex = z_edge + e * std::tan(50.0 * kDeg);
  Surface s = test::prism_xz({{-10, 0}, {-5, 0}, {-5, 6}, {-e, z_edge}, {0, apex}, {e, z_edge}, {5, 6}, {5, 0}, {10, 0}, {10, 16}, {-10, 16}},
                             -5.0, 5.0);
  s.V.col(2) += 0.1 * (s.V.col(1).array() + 5.0).matrix();
  return s;
}

// The layers marked over pixel (i, j) of 0.25 mm pixels whose column 20 begins 0.06 mm beyond the
// rising ceiling's edge (x = -e + 0.06, towards the apex) and whose row j spans y from
// -6 + 0.25 j: there the edge lies at z = 8.5 + 0.1 (-6 + 0.25 j + 1) to 0.025 mm higher.
std::set<int> layers_over_ceiling(int i, int j) {
  const Surface s = rising_ceiling();
  const double e = 5.0 - (8.1 - 6.0) / std::tan(35.0 * kDeg);
  PixelGrid g;
  g.pixel = 0.25;
  g.x0 = -e + 0.06 - 20 * g.pixel;
  g.y0 = -6.0;
  g.nx = g.ny = 96;
  std::set<int> layers;
  for (const auto& [pixel, k] : marks(s, g))
    if (pixel == i + g.nx * j) layers.insert(k);
  return layers;
}

TEST(OverhangFeatures, AStripOntoASteeperFaceAboveTheEdgeHoldsOnlyWhatLiesPastTheMarginOfTheSliceBelow) {
  // Layer 43 spans the slices at 8.5 and 8.7. With the edge u = z_e - 8.5 above the lower one,
  // that slice crosses the 35-degree face u / tan 35.26 = 1.414 u back from the edge (35.26 degrees
  // is the sheared face's slope), and a point of the 50-degree face d beyond the edge is 1.414 u + d
  // from it: contact past the margin 0.2 / tan 46 = 0.193 mm. The face reaches (0.2 - u) / tan 50
  // beyond the edge within the layer.
  // Row 20, u from 0 to 0.025: past the margin needs d > 0.158, the face reaches 0.168 at most, and
  // less where u is larger (0.147 at 0.025): no contact beyond the edge in any layer. (Marking the
  // steeper face within the margin of the edge, without the cut, put layers 43 and 44 there.)
  EXPECT_TRUE(layers_over_ceiling(20, 20).empty());
  // Row 23, u from 0.075 to 0.1: past the margin from d = 0.087 (0.052), the face reaches 0.105
  // (0.084): contact beyond column 20's side at 0.06 mm, in layer 43 alone.
  EXPECT_EQ(layers_over_ceiling(20, 23), std::set<int>{43});
  // The overhanging face's own pixels, before the edge, carry contact in both rows.
  EXPECT_FALSE(layers_over_ceiling(19, 20).empty());
  EXPECT_FALSE(layers_over_ceiling(19, 23).empty());
}

// The underside of a flat keel: two 20-degree faces meeting in a ridge that rises at 2 degrees from
// its lower end P0 = (0, 0, 8.45), 4 mm along x, 3 mm to each side. With wall_below, a vertical
// face hangs from P0 (the surface goes on down from the ridge's lower end).
Surface flat_keel(bool wall_below) {
  const double t2 = std::tan(2.0 * kDeg), t20 = std::tan(20.0 * kDeg), z0 = 8.45;
  Surface s;
  s.V.resize(wall_below ? 8 : 6, 3);
  s.V.topRows(6) << 0, 0, z0, 4, 0, z0 + 4 * t2, 0, -3, z0 + 3 * t20, 4, -3, z0 + 4 * t2 + 3 * t20, 0, 3, z0 + 3 * t20, 4, 3,
      z0 + 4 * t2 + 3 * t20;
  s.F.resize(wall_below ? 5 : 4, 3);
  s.F.topRows(4) << 0, 3, 2, 0, 1, 3, 0, 5, 1, 0, 4, 5;  // looking down, the ridge 0-1 shared
  if (wall_below) {
    s.V.bottomRows(2) << 0, -1, z0 - 3, 0, 1, z0 - 3;
    s.F.bottomRows(1) << 0, 6, 7;
  }
  return s;
}

// The (pixel, layer) pairs overhang_features() marks on the flat keel, with or without creases.
std::set<std::pair<int, int>> keel_marks(bool wall_below, bool creases) {
  const Surface s = flat_keel(wall_below);
  PixelGrid g;
  g.pixel = 0.25;
  g.x0 = -2.0;
  g.y0 = -4.0;
  g.nx = 32;
  g.ny = 32;
  OverhangRule rule;
  rule.creases = creases;
  rule.tips = false;
  return marks(s, g, rule);
}

TEST(OverhangFeatures, ARidgeBetweenOverhangingFacesShowsOnItsOwnOnlyWhereItBottomsOutWithNothingBelow) {
  // The ridge's lowest layer (42, between the slices at 8.3 and 8.5) holds 0.05 mm of it: the faces
  // reach 0.05 / tan 20.1 = 0.137 mm there, short of the margin (0.193), and are left out of it;
  // along the ridge its tip reaches 0.05 / tan 2 = 1.43 mm.
  // In open space that first slice is an island with nothing below: the ridge marks it.
  const std::set<std::pair<int, int>> open_faces = keel_marks(false, false), open_all = keel_marks(false, true);
  EXPECT_EQ(open_faces.count({8 + 16 * 32, 42}), 0u);  // pixel (8, 16) at x = 0..0.25, y = 0..0.25
  EXPECT_EQ(open_all.count({8 + 16 * 32, 42}), 1u);
  EXPECT_EQ(open_all.count({12 + 16 * 32, 42}), 1u);  // x = 1..1.25 along the ridge
  EXPECT_TRUE(std::includes(open_all.begin(), open_all.end(), open_faces.begin(), open_faces.end()));
  // With a wall below P0 the slice under layer 42 holds the wall's top at P0, and the faces' reach
  // from it decides: the ridge adds nothing to its faces.
  EXPECT_FALSE(keel_marks(true, false).empty());
  EXPECT_EQ(keel_marks(true, true), keel_marks(true, false));
}

// The highest object layer any feature of a foot (test::flared_foot) shows in.
int highest_layer_of_foot(const std::vector<Eigen::Vector2d>& flare) {
  const Surface s = test::flared_foot(flare);
  PixelGrid g;
  g.pixel = 0.25;
  g.x0 = g.y0 = -5.0;
  g.nx = g.ny = 40;
  int highest = -1;
  for (const PixelOverhang& o : overhang_features(s, FaceAdjacency(s), g, OverhangRule{})) highest = std::max(highest, o.layer_high);
  return highest;
}

TEST(OverhangFeatures, AFootsFlareShowsOnlyInTheLayersWhereItReachesTheMargin) {
  // Slices at 0.1, 0.3, 0.5, 0.7 mm; an overhang in layer k needs the slice at 0.2k + 0.1 to reach
  // 0.193 mm (0.2 / tan 46°) past the one below; its contact lies a layer under layer k - 1, so
  // only layer 2 and up put support under the first layer.
  // To r = 3.35 at z = 0.32: the slices at 0.1, 0.3, 0.5 reach 3.109, 3.328, 3.35: 0.219 past in
  // layer 1, 0.022 in layer 2. (PrusaSlicer 2.5 builds no support under this foot.)
  EXPECT_EQ(highest_layer_of_foot({{3.35, 0.32}}), 1);
  // 45° to r = 3.25 at 0.25, a wall to 0.45, a flare to 3.5 at 0.6: 0.15, 0.083 and 0.167 past in
  // layers 1, 2 and 3: no layer reaches the margin. (PrusaSlicer: no support.)
  EXPECT_LE(highest_layer_of_foot({{3.25, 0.25}, {3.25, 0.45}, {3.5, 0.6}}), 1);
  // To r = 3.8 at 0.75: 0.213 past in layers 1 to 3, 0.053 in layer 4. (PrusaSlicer: a first layer
  // of support around the foot.)
  EXPECT_EQ(highest_layer_of_foot({{3.8, 0.75}}), 3);
}

}  // namespace
}  // namespace slim
