// The support model (core/support_model/support_model.h): invariants of its estimates. The raster and the layer
// sweep beneath it, against brute-force references, are in support_sweep_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/support_model/support_model.h"
#include "support/shapes.h"

namespace slim {
namespace {

using Eigen::Vector3d;

double volume(const Surface& s, SupportModelOptions o = {}) { return estimate_support(s, o).volume_mm3; }

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
    const double v = volume(test::slab_on_stem(14.0, z));
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
  const Surface upper = test::slab_on_stem(10.0, 20.0);
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
  // The judge's protocol (eval/studies/frontier.sh): the slicer's own phase (the grid centred on
  // the part's box, which a quarter turn keeps), averaged over the quarter turns.
  SupportModelOptions own, judged;
  own.grid_phases = judged.grid_phases = 1;
  judged.turns = 2;
  EXPECT_NEAR(volume(part, judged), 0.5 * (volume(part, own) + volume(turned(90.0), own)), 1e-6 * v);
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
  const SupportEstimate e = estimate_support(test::merge(test::slab_on_stem(10.0, 20.0), test::box({-8, -8, 0}, {8, 8, 8})));
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
  down.print.direction = -Vector3d::UnitZ();
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
        o.print.direction = d;
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
  o.print.alpha_max_deg = 90.0;
  EXPECT_THROW(estimate_support(test::t_shape(), o), std::invalid_argument);
  o = {};
  o.print.direction = Vector3d::Zero();
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
