// The support model's raster (core/support_model/support_raster.h) and layer sweep (core/support_model/support_sweep.h):
// equality with brute-force references (support/support_model_reference.h), and the rules they
// encode, on rasters built from shapes or by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "core/support_model/support_raster.h"
#include "core/support_model/support_sweep.h"
#include "support/shapes.h"
#include "support/support_model_reference.h"

namespace slim {
namespace {

using Eigen::Vector3d;

// A pixel grid over the surface's bounding box with a margin, its origin off any round number.
PixelGrid grid_over(const Surface& s, double pixel) {
  const Vector3d lo = s.V.colwise().minCoeff(), hi = s.V.colwise().maxCoeff();
  PixelGrid g;
  g.pixel = pixel;
  g.x0 = lo.x() - 2.0 - 0.0123;
  g.y0 = lo.y() - 2.0 - 0.0457;
  g.nx = static_cast<int>((hi.x() - g.x0 + 2.0) / pixel) + 1;
  g.ny = static_cast<int>((hi.y() - g.y0 + 2.0) / pixel) + 1;
  return g;
}

TEST(SupportRaster, SpansEqualRayCastingThroughEveryFace) {
  const Surface s = test::merge(test::icosphere(2, 7.0, {0.31, -0.17, 9.0}), test::t_shape());
  const PixelGrid g = grid_over(s, 0.61);
  const SupportRaster r = build_support_raster(s, g, {});
  int solid = 0;
  for (int p = 0; p < g.count(); ++p) {
    const std::vector<SolidSpan> want = test::reference_spans(s, g, p);
    ASSERT_EQ(r.span_begin[p + 1] - r.span_begin[p], static_cast<int>(want.size())) << "pixel " << p;
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_NEAR(r.spans[r.span_begin[p] + i].bottom, want[i].bottom, 1e-9);
      EXPECT_NEAR(r.spans[r.span_begin[p] + i].top, want[i].top, 1e-9);
    }
    solid += !want.empty();
  }
  EXPECT_GT(solid, 100);
}

TEST(SupportRaster, RaysThroughSharedEdgesAndVerticesCountOnce) {
  // A box whose edges and vertices lie exactly on pixel centres: still one span per ray inside.
  const Surface s = test::box({0.5, 0.5, 1}, {4.5, 3.5, 5});
  PixelGrid g;
  g.nx = g.ny = 6;
  const SupportRaster r = build_support_raster(s, g, {});
  for (int p = 0; p < g.count(); ++p) {
    const double x = p % g.nx + 0.5, y = p / g.nx + 0.5;
    const int spans = r.span_begin[p + 1] - r.span_begin[p];
    const bool strictly_inside = x > 0.5 && x < 4.5 && y > 0.5 && y < 3.5;
    if (strictly_inside) {
      EXPECT_EQ(spans, 1) << x << "," << y;
    }
    if (x > 4.5 || y > 3.5) {
      EXPECT_EQ(spans, 0) << x << "," << y;
    }
    for (int i = r.span_begin[p]; i < r.span_begin[p + 1]; ++i) EXPECT_GE(r.spans[i].top, r.spans[i].bottom);
  }
}

TEST(SupportRaster, OverhangsMarkEveryPixelTheirFacesTouch) {
  // A slab tilted by 20 degrees: its underside is the only overhang (its lowest edge is a crease
  // inside the same pixels).
  const Eigen::Matrix3d tilt = test::axis_angle(Vector3d::UnitX(), 20.0 * M_PI / 180.0);
  const Surface s = test::transformed(test::box({-6.1, -4.3, 0}, {5.7, 4.9, 1.3}), tilt, {0.2, 0.1, 8.0});
  const PixelGrid g = grid_over(s, 0.53);
  const SupportRaster r = build_support_raster(s, g, {});
  std::set<int> marked, touched;
  for (const PixelOverhang& o : r.overhangs) {
    marked.insert(o.pixel);
    EXPECT_LE(o.layer_low, o.layer_high);
    EXPECT_TRUE(o.dense);
  }
  const Points n = face_normals(s);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    if (-n(f, 2) <= std::cos(46.0 * M_PI / 180.0)) continue;
    for (int p = 0; p < g.count(); ++p)
      if (test::reference_overlaps(g, p, s.V.row(s.F(f, 0)).head<2>(), s.V.row(s.F(f, 1)).head<2>(), s.V.row(s.F(f, 2)).head<2>()))
        touched.insert(p);
  }
  EXPECT_GT(touched.size(), 200u);
  EXPECT_EQ(marked, touched);
}

TEST(SupportRaster, KeelRidgesAndLowestPointsOverhangWhateverTheirFaces) {
  // A downward pyramid with 60-degree faces: no face overhangs, its tip and edges do.
  Surface s;
  s.V.resize(5, 3);
  s.V << 0, 0, 5, -4, -4, 11.93, 4, -4, 11.93, 4, 4, 11.93, -4, 4, 11.93;
  s.F.resize(6, 3);
  s.F << 0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4, 1, 2, 3, 1, 3, 4;
  const SupportRaster r = build_support_raster(s, grid_over(s, 0.5), {});
  ASSERT_FALSE(r.overhangs.empty());
  int lowest = 1 << 30;
  for (const PixelOverhang& o : r.overhangs) lowest = std::min(lowest, o.layer_low);
  EXPECT_EQ(lowest, 25);  // the layer whose slice (at 5.1) first meets the tip at z = 5
  OverhangRule steep;
  steep.max_slope_deg = 30.0;  // the edges slope 40.2 degrees: only the tip is left
  EXPECT_EQ(build_support_raster(s, grid_over(s, 0.5), steep).overhangs.size(), 1u);
}

TEST(SupportSweep, EqualsTheBruteForceSweepAtEveryPhase) {
  const Surface shapes[] = {test::t_shape(), test::mushroom(24), test::arch(12),
                            test::merge(test::slab_on_stem(9.0, 12.0), test::box({-6, -6, 0}, {6, 6, 5}))};
  for (const Surface& s : shapes) {
    PixelGrid g = grid_over(s, 0.7);
    g.x0 -= 4, g.y0 -= 4, g.nx += 12, g.ny += 12;  // room for the first layer's growth
    const SupportRaster r = build_support_raster(s, g, {});
    SlicerLayers layers;
    layers.count = static_cast<int>(s.V.col(2).maxCoeff() / 0.2) + 2;
    GridSweepSettings settings;
    const GridSupportSweep sweep(r, layers, settings);
    for (int ox = 0; ox < 4; ++ox) {
      for (int oy = 0; oy < 4; ++oy) {
        const GridSweepResult got = sweep.run(ox, oy), want = test::reference_sweep(r, layers, settings, ox, oy);
        ASSERT_GT(want.total(), 0.0);
        for (auto field : {&GridSweepResult::base_fill, &GridSweepResult::sheath, &GridSweepResult::top_interface,
                           &GridSweepResult::bottom_interface, &GridSweepResult::first_layer, &GridSweepResult::contact_area,
                           &GridSweepResult::landing_area, &GridSweepResult::column_volume})
          EXPECT_NEAR(got.*field, want.*field, 1e-9 * (1.0 + want.*field)) << "phase " << ox << "," << oy;
      }
    }
  }
}

// A flat overhang at z = 10 over a comb by hand (72 × 72 pixels of 0.5 mm, cells of 4 pixels):
// rows with a gap two cells wide, and at phase 0 a full row one cell high between two of them (the
// zigzag's lines above and below it end in the same cells and go on past the gap: inner links); a
// short row under a full row under a gapped one (the line below ends where the gap begins and
// links out to the row's end); and rows whose ends step in and out by whole cells (outer links
// along the steps). Other phases mix the rows.
SupportRaster comb_overhang() {
  SupportRaster r;
  r.grid.pixel = 0.5;
  r.grid.nx = r.grid.ny = 72;
  r.span_begin.assign(static_cast<size_t>(r.grid.count()) + 1, 0);
  auto in_comb = [](int i, int j) {
    const bool gap = i >= 24 && i < 32, wide = i >= 8 && i < 56;
    if (j >= 8 && j < 16) return i >= 8 && i < 24;
    if (j >= 16 && j < 20) return wide;  // one cell high at phase 0: between the two rows above
    if (j >= 20 && j < 32) return wide && !gap;
    if (j >= 32 && j < 36) return wide;  // one cell high at phase 0: gaps above and below
    if (j >= 36 && j < 48) return wide && !gap;
    if (j >= 48 && j < 56) return i >= 12 && i < 44;
    if (j >= 56 && j < 64) return i >= 20 && i < 52;
    return false;
  };
  for (int p = 0; p < r.grid.count(); ++p)
    if (in_comb(p % 72, p / 72)) r.overhangs.push_back({p, 49, 49, false});
  return r;
}

TEST(SupportSweep, TheZigzagsLinksAlongAStepsAndANotchAreTheBruteForceSweeps) {
  const SupportRaster r = comb_overhang();
  SlicerLayers layers;
  layers.count = 60;
  GridSweepSettings settings;
  const GridSupportSweep sweep(r, layers, settings);
  for (int ox = 0; ox < 4; ++ox)
    for (int oy = 0; oy < 4; ++oy) {
      const GridSweepResult got = sweep.run(ox, oy), want = test::reference_sweep(r, layers, settings, ox, oy);
      ASSERT_GT(want.base_fill, 0.0);
      EXPECT_NEAR(got.base_fill, want.base_fill, 1e-9 * want.base_fill) << "phase " << ox << "," << oy;
      EXPECT_NEAR(got.total(), want.total(), 1e-9 * want.total()) << "phase " << ox << "," << oy;
    }
}

// A raster by hand: n × n pixels of 0.5 mm, the part's spans at pixel (i, j) from spans_at(i, j)
// (a list of SolidSpan, sorted upwards), no overhangs yet.
template <class SpansAt>
SupportRaster raster_by_hand(int n, const SpansAt& spans_at) {
  SupportRaster r;
  r.grid.pixel = 0.5;
  r.grid.nx = r.grid.ny = n;
  r.span_begin.push_back(0);
  for (int p = 0; p < r.grid.count(); ++p) {
    for (const SolidSpan& x : spans_at(p % n, p / n)) r.spans.push_back(x);
    r.span_begin.push_back(static_cast<int>(r.spans.size()));
  }
  return r;
}

// A raster by hand: 3 × 3 cells of 4 pixels (0.5 mm), an overhang over the centre pixel (5, 5) at
// z = 10, and a block of the part from z = 4 to 6 over pixels [lo, hi]² (nothing else).
SupportRaster column_over_a_block(int lo, int hi) {
  SupportRaster r = raster_by_hand(12, [&](int i, int j) {
    return lo <= i && i <= hi && lo <= j && j <= hi ? std::vector<SolidSpan>{{4.0, 6.0}} : std::vector<SolidSpan>{};
  });
  r.overhangs.push_back({5 + 12 * 5, 49, 49, false});
  return r;
}

TEST(SupportSweep, AColumnGoesOnPastThePartsSideAndStopsInsideIt) {
  SlicerLayers layers;
  layers.count = 60;
  GridSweepSettings settings;
  // The block covers the centre cell exactly: its outline pixels have free neighbours in the cells
  // around it, so the column goes on down through it to the plate, as the slicer's does (it keeps
  // the sliver the part's side leaves) ...
  const SupportRaster side = column_over_a_block(4, 7);
  const GridSweepResult past = GridSupportSweep(side, layers, settings).run(0, 0);
  EXPECT_GT(past.first_layer, 0.0);
  EXPECT_EQ(past.layer[19], 0.0);  // no free pixel inside the block: no area
  EXPECT_GT(past.layer[10], 0.0);  // free again below it: the whole cell
  // ... a pixel wider all round, it covers the cell beyond its outline, and the column lands on it.
  const SupportRaster inside = column_over_a_block(3, 8);
  const GridSweepResult landed = GridSupportSweep(inside, layers, settings).run(0, 0);
  EXPECT_EQ(landed.first_layer, 0.0);
  EXPECT_EQ(landed.layer[10], 0.0);
  EXPECT_DOUBLE_EQ(landed.landing_area, 16 * 0.25);  // the cell's 16 pixels
  for (const SupportRaster* r : {&side, &inside}) {
    const GridSweepResult got = GridSupportSweep(*r, layers, settings).run(0, 0);
    const GridSweepResult want = test::reference_sweep(*r, layers, settings, 0, 0);
    EXPECT_NEAR(got.total(), want.total(), 1e-9 * want.total());
    EXPECT_NEAR(got.column_volume, want.column_volume, 1e-9 * want.column_volume);
  }
}


// A raster by hand: 3 × 3 cells of 4 pixels (0.5 mm), an overhang over pixel (6, 5) at z = 10 and,
// along every row, a bore's floor and walls under the centre cell (pixels 4..7): pixels 5 and 6
// filled from the plate to z = 4, the cell's edge pixels 4 and 7 from z = 2 to 8, and pixels 3 and
// 8 beside them (the next cells) from wall_bottom to 8, or never (walls straight up at the cell's
// edges).
SupportRaster column_in_a_bore(double wall_bottom) {
  SupportRaster r = raster_by_hand(12, [&](int i, int) {
    std::vector<SolidSpan> spans;
    if (i == 5 || i == 6) spans.push_back({0.0, 4.0});
    if (i == 4 || i == 7) spans.push_back({2.0, 8.0});
    if ((i == 3 || i == 8) && wall_bottom < 8.0) spans.push_back({wall_bottom, 8.0});
    return spans;
  });
  r.overhangs.push_back({6 + 12 * 5, 49, 49, false});
  return r;
}

TEST(SupportSweep, AColumnInABoreLandsOnItsFloorWhereTheWallsOutlineHasLeftItsCell) {
  SlicerLayers layers;
  layers.count = 60;
  const GridSweepSettings settings;
  // Walls straight up: where the floor fills the rest of the cell, its edge pixels, filled, lie on
  // the part's outline, so a sliver of the cell may be free beside a wall, and the column goes on
  // down past the floor to the plate, as it goes past a part's side.
  const SupportRaster straight = column_in_a_bore(8.0);
  const GridSweepResult past = GridSupportSweep(straight, layers, settings).run(0, 0);
  EXPECT_GT(past.first_layer, 0.0);
  // The walls' outsides leaning out above z = 2 (pixels 3 and 8 filled from 4.2, the slice at 4.3
  // on; the edge pixels from the slice at 2.1): from the slice at 3.3, halfway, their outlines lie
  // past the midpoints between the edge pixels and those, in the next cells, so the cell has no
  // free sliver between 3.3 and the floor's top, and the column lands on the floor.
  const SupportRaster leaning = column_in_a_bore(4.2);
  const GridSweepResult landed = GridSupportSweep(leaning, layers, settings).run(0, 0);
  EXPECT_EQ(landed.first_layer, 0.0);
  EXPECT_EQ(landed.layer[5], 0.0);
  EXPECT_DOUBLE_EQ(landed.landing_area, 16 * 0.25);  // the floor's and the walls' tops: the whole cell
  for (const SupportRaster* r : {&straight, &leaning}) {
    const GridSweepResult got = GridSupportSweep(*r, layers, settings).run(0, 0);
    const GridSweepResult want = test::reference_sweep(*r, layers, settings, 0, 0);
    ASSERT_GT(want.total(), 0.0);
    EXPECT_NEAR(got.total(), want.total(), 1e-9 * want.total());
    EXPECT_NEAR(got.landing_area, want.landing_area, 1e-9 * (1.0 + want.landing_area));
  }
}


// A raster by hand: 4 × 4 cells of 4 pixels (0.5 mm), the part filling pixel columns i < 8 from
// the plate to z = 5, and overhangs standing on its top (layer 25, whose slice below lies at 4.9)
// over the given pixels.
SupportRaster overhangs_on_a_top(const std::vector<int>& pixels) {
  SupportRaster r = raster_by_hand(16, [](int i, int) { return i < 8 ? std::vector<SolidSpan>{{0.0, 5.0}} : std::vector<SolidSpan>{}; });
  for (int p : pixels) r.overhangs.push_back({p, 25, 25, false});
  return r;
}

TEST(SupportSweep, AContactOnThePartsOutlineReachesItsCellAndOneInsideThePartIsHidden) {
  // Cells from pixel 2 on (phase 2, 0): pixels 6..9 make a cell that the part's side crosses.
  // An overhang over pixel (7, 2), on the outline (pixel 8 beside it is free), is a contact there:
  // the slicer rasterises a contact with any coverage, so the sliver reaches the cell, whose free
  // pixels 8 and 9 become a column. One over pixel (6, 10), inside the part (its four neighbours
  // filled too), is hidden: nothing, though its cell has the same free pixels.
  SlicerLayers layers;
  layers.count = 40;
  const GridSweepSettings settings;
  const int outline = 7 + 16 * 2, inside = 6 + 16 * 10;
  const GridSweepResult on_outline = GridSupportSweep(overhangs_on_a_top({outline}), layers, settings).run(2, 0);
  EXPECT_GT(on_outline.contact_area, 0.0);
  EXPECT_GT(on_outline.first_layer, 0.0);  // the column stands on the plate beside the part
  const GridSweepResult hidden = GridSupportSweep(overhangs_on_a_top({inside}), layers, settings).run(2, 0);
  EXPECT_EQ(hidden.total(), 0.0);
  EXPECT_EQ(hidden.contact_area, 0.0);
  const GridSweepResult both = GridSupportSweep(overhangs_on_a_top({outline, inside}), layers, settings).run(2, 0);
  EXPECT_DOUBLE_EQ(both.total(), on_outline.total());
  for (const std::vector<int>& pixels : {std::vector<int>{outline}, std::vector<int>{inside}, std::vector<int>{outline, inside}}) {
    const SupportRaster r = overhangs_on_a_top(pixels);
    const GridSweepResult got = GridSupportSweep(r, layers, settings).run(2, 0), want = test::reference_sweep(r, layers, settings, 2, 0);
    EXPECT_NEAR(got.total(), want.total(), 1e-9 * (1.0 + want.total()));
    EXPECT_NEAR(got.contact_area, want.contact_area, 1e-9 * (1.0 + want.contact_area));
  }
}
}  // namespace
}  // namespace slim
