// The support model (core/support_model.h): invariants, and equality with brute-force references
// (support/support_model_reference.h) for the raster and the layer sweep.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>

#include "core/support_model.h"
#include "core/support_raster.h"
#include "core/support_sweep.h"
#include "support/shapes.h"
#include "support/support_model_reference.h"

namespace slim {
namespace {

using Eigen::Vector3d;

// A slab [-w/2, w/2]² × [z, z + 2] on a 4 × 4 stem from the plate (the stem reaches into it).
Surface slab_on_stem(double width, double z) {
  return test::merge(test::box({-2, -2, 0}, {2, 2, z + 1}), test::box({-width / 2, -width / 2, z}, {width / 2, width / 2, z + 2}));
}

double volume(const Surface& s, SupportModelOptions o = {}) { return estimate_support(s, o).volume_mm3; }

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
                            test::merge(slab_on_stem(9.0, 12.0), test::box({-6, -6, 0}, {6, 6, 5}))};
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

// A raster by hand: 3 × 3 cells of 4 pixels (0.5 mm), an overhang over the centre pixel (5, 5) at
// z = 10, and a block of the part from z = 4 to 6 over pixels [lo, hi]² (nothing else).
SupportRaster column_over_a_block(int lo, int hi) {
  SupportRaster r;
  r.grid.pixel = 0.5;
  r.grid.nx = r.grid.ny = 12;
  r.span_begin.push_back(0);
  for (int p = 0; p < r.grid.count(); ++p) {
    const int i = p % 12, j = p / 12;
    if (lo <= i && i <= hi && lo <= j && j <= hi) r.spans.push_back({4.0, 6.0});
    r.span_begin.push_back(static_cast<int>(r.spans.size()));
  }
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

TEST(SupportModel, ZeroForPartsWithoutOverhangs) {
  EXPECT_EQ(volume(test::box({0, 0, 0}, {20, 10, 30})), 0.0);
  EXPECT_EQ(volume(test::printable_mushroom()), 0.0);
  EXPECT_EQ(volume(test::l_bracket()), 0.0);
  // An overhang lower than the first layer plus the contact gap gets no support either.
  EXPECT_EQ(volume(test::merge(test::box({-2, -2, 0}, {2, 2, 6}), test::box({-8, -8, 0.25}, {8, 8, 2}))), 0.0);
}

TEST(SupportModel, MoreSupportTheHigherTheOverhang) {
  double previous = 0.0, previous_step = 0.0;
  for (double z : {6.0, 12.0, 18.0, 24.0, 30.0}) {
    const double v = volume(slab_on_stem(14.0, z));
    EXPECT_GT(v, previous) << z;
    if (previous > 0) {  // the columns grow by the same area per mm: steps nearly equal
      const double step = v - previous;
      if (previous_step > 0) {
        EXPECT_NEAR(step, previous_step, 0.05 * previous_step) << z;
      }
      previous_step = step;
    }
    previous = v;
  }
}

TEST(SupportModel, AShadowedOverhangStandsOnThePartBelow) {
  const Surface upper = slab_on_stem(10.0, 20.0);
  const Surface lower = test::box({-8, -8, 0}, {8, 8, 8});  // wider, below it: a roof for nothing
  const Surface both = test::merge(upper, lower);
  const SupportEstimate alone = estimate_support(upper), stacked = estimate_support(both);
  EXPECT_EQ(alone.landing_area_mm2, 0.0);
  // Every column lands on the lower block: about the slab's cells (10 mm -> 4 or 5 cells a side).
  EXPECT_GT(stacked.landing_area_mm2, 0.8 * 10 * 10);
  EXPECT_LT(stacked.landing_area_mm2, 15.0 * 15.0);
  EXPECT_EQ(stacked.first_layer_mm3, 0.0);  // nothing reaches the plate
  // The columns are 12 mm shorter than the 20 mm ones to the plate.
  EXPECT_NEAR(stacked.column_volume_mm3 / alone.column_volume_mm3, (20.0 - 8.0) / 20.0, 0.08);
  EXPECT_LT(stacked.volume_mm3, alone.volume_mm3);
}

TEST(SupportModel, TinyIslandsBecomeWholeGridCells) {
  // Pins 0.4 mm and 2 mm thick sticking out of a wall by 0.6 cells at z = 15, both inside one cell
  // of the slicer's own phase (the wall, 9 cells long, puts the bounding-box centre so): the grid
  // stretches either to that whole cell, less the wall and the gap to it.
  SupportModelOptions o;
  o.grid_phases = 1;
  const double cell = o.grid_spacing, reach = 0.6 * cell;
  auto pin = [&](double t) {
    const Surface wall = test::box({-9 * cell, -4.5 * cell, 0}, {0, 4.5 * cell, 20});
    return test::merge(wall, test::box({-0.5, 0.15 * cell, 15}, {reach, 0.15 * cell + t, 15 + t}));
  };
  const SupportEstimate thin = estimate_support(pin(0.4), o), thick = estimate_support(pin(2.0), o);
  ASSERT_GT(thin.volume_mm3, 0.0);
  const double free_width = 0.5 * cell + 0.5 * reach - o.xy_gap;  // the cell beside the wall
  const double height = 15.0 - o.contact_distance;
  EXPECT_NEAR(thin.column_volume_mm3 / height, free_width * cell, 0.1 * free_width * cell);
  EXPECT_NEAR(thin.column_volume_mm3, thick.column_volume_mm3, 1e-9 * thick.column_volume_mm3);
  EXPECT_NEAR(thin.volume_mm3, thick.volume_mm3, 1e-9 * thick.volume_mm3);
}

TEST(SupportModel, TurningAboutThePrintAxisChangesLittle) {
  const Surface bunny = test::load_mesh(test::sample_bunny_path());
  const Surface part = test::transformed(bunny, 6.0 * Eigen::Matrix3d::Identity());  // about 60 mm
  auto turned = [&](double deg) { return test::transformed(part, test::axis_angle(Vector3d::UnitZ(), deg * M_PI / 180.0)); };
  // A half turn maps the grid, its phases and the support lines (along x, on cell boundaries)
  // onto themselves: the same figure.
  const double v = volume(part);
  ASSERT_GT(v, 1000.0);
  EXPECT_NEAR(volume(turned(180.0)), v, 1e-9 * v);
  // A quarter turn lays the lines along the part's other axis, which the slicer feels too (by 8%
  // on this part, turn 90 against turn 0); other angles meet the grid at another angle.
  EXPECT_NEAR(volume(turned(90.0)), v, 0.10 * v);
  for (double deg : {10.0, 30.0, 45.0}) EXPECT_NEAR(volume(turned(deg)), v, 0.05 * v) << deg;
  // turns = 2 averages the part as given and turned by a quarter.
  SupportModelOptions two;
  two.turns = 2;
  EXPECT_NEAR(volume(part, two), 0.5 * (v + volume(turned(90.0))), 1e-6 * v);
  // Every pixel offset as a phase samples the same average as the default four.
  SupportModelOptions all;
  all.grid_phases = all.pixels_per_cell * all.pixels_per_cell;
  EXPECT_NEAR(volume(part, all), v, 0.02 * v);
}

TEST(SupportModel, ASpeckThatMovesTheGridBarelyMovesTheAverage) {
  // A 0.1 mm speck on the plate beside the part moves its bounding box, and with it the slicer's
  // grid, by a fraction of a cell: the slicer's own phase jumps by several % (5.8% here), the
  // phase average by less than half of that (2.5% with 4 phases, 1.5% with 16), so an optimizer
  // gains little by moving the box against the grid.
  Surface part = test::load_mesh(test::sample_bunny_path());
  part.V *= 6.0;
  const double xmax = part.V.col(0).maxCoeff(), y = part.V.col(1).mean();
  auto spread = [&](int phases) {
    SupportModelOptions o;
    o.grid_phases = phases;
    double lo = INFINITY, hi = 0.0;
    for (double d = 0.5; d < 3.4; d += 0.357) {
      const double v = volume(test::merge(part, test::box({xmax + d, y, 0}, {xmax + d + 0.1, y + 0.1, 0.1})), o);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    return (hi - lo) / hi;
  };
  const double own = spread(1), average = spread(4), finer = spread(16);
  EXPECT_GT(own, 0.03);
  EXPECT_LT(average, 0.03);
  EXPECT_LT(average, own / 2);
  EXPECT_LT(finer, average);
}

// The first phase of the mean is the slicer's own (the grid centred on the part's box), bit for bit:
// the optimizer reads the prediction for the file as placed from the estimate it makes anyway.
TEST(SupportModel, TheFirstPhaseIsTheSlicersOwn) {
  for (const Surface& s : {test::t_shape(), test::refined(test::arch(), 1), test::box_with_windows(5.0)}) {
    SupportModelOptions own;
    own.grid_phases = 1;
    const SupportEstimate mean = estimate_support(s), one = estimate_support(s, own);
    ASSERT_EQ(mean.phase_mm3.size(), 4u);
    EXPECT_EQ(mean.phase_mm3.front(), one.volume_mm3);
    EXPECT_GT(one.volume_mm3, 0.0);
  }
}

TEST(SupportModel, ThePartsAndTheLayersAddUpToTheWhole) {
  const SupportEstimate e = estimate_support(test::merge(slab_on_stem(10.0, 20.0), test::box({-8, -8, 0}, {8, 8, 8})));
  ASSERT_GT(e.bottom_interface_mm3, 0.0);
  EXPECT_NEAR(e.base_fill_mm3 + e.sheath_mm3 + e.top_interface_mm3 + e.bottom_interface_mm3 + e.first_layer_mm3, e.volume_mm3,
              1e-9 * e.volume_mm3);
  double layers = 0.0;
  for (double v : e.layer_mm3) layers += v;
  EXPECT_NEAR(layers, e.volume_mm3, 1e-9 * e.volume_mm3);
  double phases = 0.0;
  for (double v : e.phase_mm3) phases += v / e.phase_mm3.size();
  EXPECT_NEAR(phases, e.volume_mm3, 1e-9 * e.volume_mm3);
  EXPECT_LE(e.min_phase_mm3, e.volume_mm3);
  EXPECT_GE(e.max_phase_mm3, e.volume_mm3);
}

TEST(SupportModel, SameResultOnAnyThreadCountAndPrintDirection) {
  const Surface t = test::t_shape();
  SupportModelOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const SupportEstimate a = estimate_support(t, one), b = estimate_support(t, two);
  EXPECT_EQ(a.volume_mm3, b.volume_mm3);
  EXPECT_EQ(a.phase_mm3, b.phase_mm3);
  const Surface open = test::box_with_windows(5.0);  // sliced layer by layer, in parallel
  EXPECT_EQ(estimate_support(open, one).phase_mm3, estimate_support(open, two).phase_mm3);
  // The same part given upside down with the print direction -Z.
  SupportModelOptions down;
  down.print_direction = -Vector3d::UnitZ();
  const Surface flipped_t = test::transformed(t, test::axis_angle(Vector3d::UnitX(), M_PI));
  EXPECT_NEAR(volume(flipped_t, down), a.volume_mm3, 1e-6 * a.volume_mm3);
}

// The optimizer keeps one model for all its iterates, the orientation search one for all its
// poses: the faces' adjacency is found once, and every estimate is estimate_support's, bit for bit,
// on one thread or two (over 4096 faces the raster works through its ranges on both).
TEST(SupportModel, OneModelOfAMeshGivesEstimateSupportsBitsInEveryPose) {
  // A closed mesh large enough for the raster's parallel ranges, and an open one (read slice by
  // slice: a box with a window in its side).
  const Surface m = test::refined(test::mushroom(), 2), open = test::box_with_windows(5.0);
  ASSERT_GT(m.F.rows(), 4096);
  for (const Surface* mesh : {&m, &open}) {
    SupportModel model(mesh->F, mesh->V.rows());
    for (const Vector3d& d : {Vector3d(0, 0, 1), Vector3d(0.3, -0.2, 1), Vector3d(1, 0, 0.2)})
      for (int threads : {1, 2}) {
        SupportModelOptions o;
        o.print_direction = d;
        o.threads = threads;
        const Surface moved = test::transformed(*mesh, Eigen::Matrix3d::Identity(), Vector3d(threads, 0.5, 0));
        const SupportEstimate a = model.estimate(moved.V, o), b = estimate_support(moved, o);
        EXPECT_GT(a.volume_mm3, 0.0);
        EXPECT_EQ(a.volume_mm3, b.volume_mm3) << d.transpose() << " " << threads;
        EXPECT_EQ(a.phase_mm3, b.phase_mm3);
        EXPECT_EQ(a.layer_mm3, b.layer_mm3);
      }
  }
  // The model keeps the part in the print frame from call to call: a mirrored pose (inside out,
  // its faces turned over) between two others leaves nothing behind.
  SupportModel model(m.F, m.V.rows());
  const Surface mirrored = test::transformed(m, Eigen::Vector3d(-1, 1, 1).asDiagonal(), Vector3d::Zero());
  for (const Surface* pose : {&m, &mirrored, &m, &mirrored}) {
    const SupportEstimate a = model.estimate(pose->V), b = estimate_support(*pose);
    EXPECT_GT(a.volume_mm3, 0.0);
    EXPECT_EQ(a.volume_mm3, b.volume_mm3);
    EXPECT_EQ(a.phase_mm3, b.phase_mm3);
  }
  Triangles bad = m.F;
  bad(3, 1) = static_cast<int>(m.V.rows());
  EXPECT_THROW(SupportModel(bad, m.V.rows()), std::invalid_argument);
  EXPECT_THROW(model.estimate(m.V.topRows(m.V.rows() - 1)), std::invalid_argument);
  Points nan = m.V;
  nan(0, 0) = NAN;
  EXPECT_THROW(model.estimate(nan), std::invalid_argument);
}

TEST(SupportModel, RejectsBadInput) {
  SupportModelOptions o;
  EXPECT_THROW(estimate_support(Surface{}, o), std::invalid_argument);
  o.grid_phases = 3;
  EXPECT_THROW(estimate_support(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.alpha_max_deg = 90.0;
  EXPECT_THROW(estimate_support(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.print_direction = Vector3d::Zero();
  EXPECT_THROW(estimate_support(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.slice_max_gap = -1.0;
  EXPECT_THROW(estimate_support(test::t_shape(), o), std::invalid_argument);
}

// A part whose faces are turned over (inside out: every normal into the part) is the same part:
// the model turns its faces back in the print frame, and reads their edges as they then run. Its
// estimate is the part's own, bit for bit, by estimate_support and by one model through both; a
// closed part, a mirrored one, and an open one (a box with a window, read slice by slice).
TEST(SupportModel, AnInsideOutPartIsEstimatedAsThePartItself) {
  const Surface m = test::refined(test::mushroom(), 1);
  const Surface mirrored = test::transformed(m, Eigen::Vector3d(-1, 1, 1).asDiagonal(), Vector3d::Zero());
  for (const Surface& part : {m, flipped(mirrored), test::box_with_windows(5.0)}) {
    const Surface inside_out = flipped(part);
    const SupportEstimate a = estimate_support(part), b = estimate_support(inside_out);
    EXPECT_GT(a.volume_mm3, 0.0);
    EXPECT_EQ(a.volume_mm3, b.volume_mm3);
    EXPECT_EQ(a.phase_mm3, b.phase_mm3);
    SupportModel model(inside_out.F, inside_out.V.rows());
    for (int k = 0; k < 2; ++k) EXPECT_EQ(model.estimate(inside_out.V).volume_mm3, a.volume_mm3) << k;
  }
}

}  // namespace
}  // namespace slim
