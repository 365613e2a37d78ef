// Slices as a slicer cuts them (core/support_model/layer_slices.h) and the support raster read from them
// (core/support_model/slice_raster.h): closed meshes slice into closed loops of their exact cross-section and
// read as the ray raster does; holes are closed across small gaps, wider ones empty the slice and
// the slice above stands on nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"
#include "core/support_model/layer_slices.h"
#include "core/support_model/slice_raster.h"
#include "core/support_model/support_raster.h"
#include "core/support_model/support_sweep.h"
#include "support/shapes.h"

namespace slim {
namespace {

using Eigen::Vector3d;

double signed_area(const Polyline2& p) {
  double a = 0.0;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

double loops_area(const LayerSlice& s) {
  double a = 0.0;
  for (const Polyline2& p : s.loops) a += signed_area(p);
  return a;
}

std::vector<LayerSlice> slice(const Surface& s, const std::vector<double>& heights, double gap = 2.0) {
  return slice_layers(s, FaceAdjacency(s), heights, gap);
}

TEST(LayerSlices, AClosedMeshSlicesIntoClosedLoopsOfItsCrossSection) {
  // A 20 x 14 box turned about +Z, with a 6 x 4 cavity (inside-out box) inside it, and beside it a
  // second box: material on the loops' left, so the cavity's loop runs clockwise.
  const Eigen::Matrix3d turn = test::axis_angle(Vector3d::UnitZ(), 0.37);
  const Surface outer = test::transformed(test::box({0, 0, 0}, {20, 14, 10}), turn, {1.3, -0.7, 0});
  const Surface cavity = test::transformed(flipped(test::box({5, 5, 3}, {11, 9, 7})), turn, {1.3, -0.7, 0});
  const Surface s = test::merge(test::merge(outer, cavity), test::box({30, 0, 0}, {33, 2, 5}));
  const std::vector<double> heights = {8.5, 1.0, 5.0, 9.99, 12.0};
  std::vector<LayerSlice> slices;
  {
    const ThreadScope one(1);
    slices = slice(s, heights);
  }
  const std::vector<LayerSlice> on_two = [&] {
    const ThreadScope two(2);
    return slice(s, heights);
  }();
  const std::vector<size_t> loops = {1, 2, 3, 1, 0};
  const std::vector<double> area = {280, 286, 280 - 24 + 6, 280, 0};
  for (size_t h = 0; h < heights.size(); ++h) {
    SCOPED_TRACE(heights[h]);
    EXPECT_TRUE(slices[h].dropped.empty());
    EXPECT_EQ(slices[h].loops.size(), loops[h]);
    EXPECT_NEAR(loops_area(slices[h]), area[h], 1e-9);
    int clockwise = 0;
    for (const Polyline2& p : slices[h].loops) clockwise += signed_area(p) < 0;
    EXPECT_EQ(clockwise, heights[h] > 3 && heights[h] < 7 ? 1 : 0);
    ASSERT_EQ(on_two[h].loops.size(), slices[h].loops.size());
    for (size_t i = 0; i < slices[h].loops.size(); ++i) EXPECT_EQ(on_two[h].loops[i], slices[h].loops[i]);
  }
}

TEST(LayerSlices, AHoleWiderThanTheGapEmptiesTheSlicesThroughIt) {
  const Surface s = test::box_with_windows(5.0);  // a 5 mm window over z in [6.25, 13.75]
  const std::vector<LayerSlice> slices = slice(s, {3.0, 10.0, 17.0});
  for (size_t h : {0, 2}) {
    EXPECT_EQ(slices[h].loops.size(), 1u);
    EXPECT_TRUE(slices[h].dropped.empty());
    EXPECT_NEAR(loops_area(slices[h]), 400.0, 1e-9);
  }
  EXPECT_TRUE(slices[1].loops.empty());
  ASSERT_EQ(slices[1].dropped.size(), 1u);
  // The lost chain runs from one side of the window to the other, material on its left: closed
  // by a straight line across the window it is the whole section.
  EXPECT_NEAR((slices[1].dropped[0].front() - slices[1].dropped[0].back()).norm(), 5.0, 1e-9);
  EXPECT_NEAR(signed_area(slices[1].dropped[0]), 400.0, 1e-9);
  // A slicer that closes gaps up to 6 mm closes this one.
  const std::vector<LayerSlice> wide = slice(s, {10.0}, 6.0);
  EXPECT_EQ(wide[0].loops.size(), 1u);
  EXPECT_TRUE(wide[0].dropped.empty());
  EXPECT_NEAR(loops_area(wide[0]), 400.0, 1e-9);
}

TEST(LayerSlices, OpenChainsAreJoinedAcrossGapsUnderTheLimit) {
  // Windows 1.25 mm wide in two opposite sides: through them the section falls into two chains,
  // each end 1.25 mm from the other chain's start.
  const Surface s = test::box_with_windows(1.25, 2);
  const std::vector<LayerSlice> joined = slice(s, {10.0});
  EXPECT_TRUE(joined[0].dropped.empty());
  ASSERT_EQ(joined[0].loops.size(), 1u);
  EXPECT_NEAR(loops_area(joined[0]), 400.0, 1e-9);
  const std::vector<LayerSlice> apart = slice(s, {10.0}, 1.0);
  EXPECT_TRUE(apart[0].loops.empty());
  EXPECT_EQ(apart[0].dropped.size(), 2u);
}

TEST(LayerSlices, RejectsBadInput) {
  const Surface s = test::box({0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(slice(s, {0.5}, -1.0), std::invalid_argument);
  EXPECT_THROW(slice(s, {NAN}), std::invalid_argument);
  EXPECT_TRUE(slice(s, {}).empty());
}

// The layers each pixel's spans make solid, as the sweep reads them.
std::vector<std::set<int>> solid_layers(const SupportRaster& r, const SlicerLayers& L) {
  std::vector<std::set<int>> out(static_cast<size_t>(r.grid.count()));
  for (int p = 0; p < r.grid.count(); ++p)
    for (int s = r.span_begin[p]; s < r.span_begin[p + 1]; ++s)
      for (int k = L.first_slice_at_or_above(r.spans[s].bottom); k <= L.last_slice_at_or_below(r.spans[s].top) && k < L.count; ++k)
        out[p].insert(k);
  return out;
}

PixelGrid grid_over(const Surface& s, double pixel) {
  const Vector3d lo = s.V.colwise().minCoeff(), hi = s.V.colwise().maxCoeff();
  PixelGrid g;
  g.pixel = pixel;
  g.x0 = lo.x() - 3.0173;
  g.y0 = lo.y() - 3.0291;
  g.nx = static_cast<int>((hi.x() - g.x0 + 3.0) / pixel) + 1;
  g.ny = static_cast<int>((hi.y() - g.y0 + 3.0) / pixel) + 1;
  return g;
}

SlicerLayers layers_of(const Surface& s) {
  SlicerLayers L;
  L.count = static_cast<int>(std::ceil((s.V.col(2).maxCoeff() - L.first_height) / L.height)) + 2;
  return L;
}

TEST(SliceRaster, AClosedMeshReadsAsTheRayRaster) {
  // Overlapping closed parts (a ball through a T) and the sample bunny at 60 mm: slice by slice,
  // every pixel is solid in the same layers as along its ray, and the sweep gives the same bits.
  Surface bunny = test::sample_bunny();
  bunny.V *= 60.0 / (bunny.V.colwise().maxCoeff() - bunny.V.colwise().minCoeff()).maxCoeff();
  bunny.V.col(2).array() -= bunny.V.col(2).minCoeff();
  for (const Surface& s : {test::merge(test::icosphere(2, 7.0, {0.31, -0.17, 9.0}), test::t_shape()), bunny}) {
    const FaceAdjacency adj(s);
    const PixelGrid g = grid_over(s, 0.714);
    OverhangRule rays, slices;
    slices.slices = true;
    const SupportRaster a = build_support_raster(s, adj, g, rays), b = build_support_raster(s, adj, g, slices);
    const SlicerLayers L = layers_of(s);
    EXPECT_EQ(solid_layers(a, L), solid_layers(b, L));
    ASSERT_EQ(a.overhangs.size(), b.overhangs.size());  // no contour lost: no overhang added
    const GridSweepSettings settings;
    for (int phase : {0, 3}) EXPECT_EQ(GridSupportSweep(a, L, settings).run(phase, 3 - phase).total(),
                                       GridSupportSweep(b, L, settings).run(phase, 3 - phase).total());
  }
}

TEST(SliceRaster, TheSliceAboveALostContourStandsOnNothing) {
  const Surface open = test::box_with_windows(5.0), closed = test::refined(test::box({-10, -10, 0}, {10, 10, 20}), 4);
  const PixelGrid g = grid_over(closed, 0.714);
  OverhangRule rule;
  rule.slices = true;
  const SupportRaster r = build_support_raster(open, FaceAdjacency(open), g, rule);
  const SlicerLayers L = layers_of(closed);
  const std::vector<std::set<int>> solid = solid_layers(r, L);
  const int below = L.last_slice_at_or_below(6.25), first_lost = below + 1, above = L.first_slice_at_or_above(13.75);
  int inside = 0, stands_on_nothing = 0;
  for (int p = 0; p < g.count(); ++p) {
    const double x = g.x0 + (p % g.nx + 0.5) * g.pixel, y = g.y0 + (p / g.nx + 0.5) * g.pixel;
    if (std::abs(x) >= 10 || std::abs(y) >= 10) {
      EXPECT_TRUE(solid[p].empty()) << p;
      continue;
    }
    ++inside;
    // Solid up to the window, empty through it, solid again above it.
    for (int k = 0; k < L.count; ++k) EXPECT_EQ(solid[p].count(k), (k <= below || k >= above) && L.slice_z(k) < 20 ? 1u : 0u) << k;
    EXPECT_GT(above, first_lost);
    for (const PixelOverhang& o : r.overhangs)
      if (o.pixel == p && o.layer_low == above && o.dense) ++stands_on_nothing;
  }
  EXPECT_EQ(stands_on_nothing, inside);
  // Its faces overhang as the closed box's do (its bottom, on the plate): the rest came from the
  // lost slices.
  const SupportRaster shut = build_support_raster(closed, FaceAdjacency(closed), g, rule);
  EXPECT_EQ(r.overhangs.size(), shut.overhangs.size() + static_cast<size_t>(inside));
}

// The winding number of closed polylines around a point (each polyline's last point joins its
// first): the plain sum over edges, for the reference below.
int winding(const std::vector<const Polyline2*>& polygons, const Eigen::Vector2d& c) {
  int w = 0;
  for (const Polyline2* poly : polygons)
    for (size_t i = 0; i < poly->size(); ++i) {
      const Eigen::Vector2d& p = (*poly)[i];
      const Eigen::Vector2d& q = (*poly)[(i + 1) % poly->size()];
      if ((p.y() <= c.y()) == (q.y() <= c.y())) continue;
      const double x = p.x() + (c.y() - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
      if (x < c.x()) w += q.y() > p.y() ? -1 : 1;
    }
  return w;
}

TEST(SliceRaster, EqualsEveryPixelAndSliceTestedOnItsOwn) {
  // A ball with a window in its side (faces beyond x = 7 removed: slices through it have gaps up
  // to 14 mm, and near its top and bottom under 2 mm, which the slicer closes), tall enough for
  // several of the raster's blocks of slices.
  const Surface ball = test::icosphere(3, 10.0, {0.123, -0.071, 10.0});
  std::vector<Eigen::Vector3i> kept;
  for (Eigen::Index f = 0; f < ball.F.rows(); ++f) {
    double cx = 0;
    for (int k = 0; k < 3; ++k) cx += ball.V(ball.F(f, k), 0) / 3.0;
    if (cx < 7.0) kept.emplace_back(ball.F.row(f).transpose());
  }
  Surface open{ball.V, Triangles(static_cast<Eigen::Index>(kept.size()), 3)};
  for (size_t f = 0; f < kept.size(); ++f) open.F.row(static_cast<Eigen::Index>(f)) = kept[f].transpose();
  open.V.col(2).array() -= open.V.col(2).minCoeff();
  const FaceAdjacency adj(open);
  const PixelGrid g = grid_over(open, 0.714);
  OverhangRule rule;
  rule.slices = true;
  const SupportRaster r = build_support_raster(open, adj, g, rule);
  const SlicerLayers L = layers_of(open);
  std::vector<double> heights;
  for (int k = 0; L.slice_z(k) <= open.V.col(2).maxCoeff(); ++k) heights.push_back(L.slice_z(k));
  ASSERT_GT(heights.size(), 64u);
  const std::vector<LayerSlice> slices = slice_layers(open, adj, heights, rule.slice_max_gap);
  std::vector<std::set<int>> solid(static_cast<size_t>(g.count()));
  std::set<std::pair<int, int>> lost_below;  // (pixel, layer) of the overhangs the lost slices make
  int dropped_layers = 0;
  for (size_t k = 0; k < heights.size(); ++k) {
    std::vector<const Polyline2*> loops, with_lost;
    for (const Polyline2& p : slices[k].loops) loops.push_back(&p), with_lost.push_back(&p);
    for (const Polyline2& p : slices[k].dropped) with_lost.push_back(&p);
    dropped_layers += !slices[k].dropped.empty();
    std::vector<const Polyline2*> below, below_lost;
    if (k > 0) {
      for (const Polyline2& p : slices[k - 1].loops) below.push_back(&p), below_lost.push_back(&p);
      for (const Polyline2& p : slices[k - 1].dropped) below_lost.push_back(&p);
    }
    for (int p = 0; p < g.count(); ++p) {
      const Eigen::Vector2d c(g.x0 + (p % g.nx + 0.5) * g.pixel, g.y0 + (p / g.nx + 0.5) * g.pixel);
      const bool here = winding(loops, c) != 0;
      if (here) solid[static_cast<size_t>(p)].insert(static_cast<int>(k));
      if (k > 0 && !slices[k - 1].dropped.empty() && here && winding(below, c) == 0 && winding(below_lost, c) != 0)
        lost_below.insert({p, static_cast<int>(k)});
    }
  }
  EXPECT_GT(dropped_layers, 10);
  EXPECT_EQ(solid_layers(r, L), solid);
  std::set<std::pair<int, int>> marked;
  const SupportRaster shut = build_support_raster(open, adj, g, OverhangRule{});  // the faces' own overhangs
  std::multiset<std::tuple<int, int, int, bool>> faces_only, all;
  for (const PixelOverhang& o : shut.overhangs) faces_only.insert({o.pixel, o.layer_low, o.layer_high, o.dense});
  for (const PixelOverhang& o : r.overhangs) all.insert({o.pixel, o.layer_low, o.layer_high, o.dense});
  for (const auto& o : faces_only) {
    auto it = all.find(o);
    ASSERT_NE(it, all.end());
    all.erase(it);
  }
  for (const auto& [pixel, low, high, dense] : all) {
    EXPECT_EQ(low, high);
    EXPECT_TRUE(dense);
    marked.insert({pixel, low});
  }
  EXPECT_EQ(marked, lost_below);
  EXPECT_FALSE(lost_below.empty());
}

}  // namespace
}  // namespace slim
