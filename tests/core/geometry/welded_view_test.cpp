// core/welded_view: coincident vertices merged for the core's topology, every result mapped back
// to each copy, the caller's vertex list unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/geometry/surface.h"
#include "core/geometry/welded_view.h"
#include "support/shapes.h"

using namespace slim;

namespace {
// Every face with its own three corners, as STL stores them.
Surface soup(const Surface& s) {
  Surface out;
  out.V.resize(3 * s.F.rows(), 3);
  out.F.resize(s.F.rows(), 3);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      out.V.row(3 * f + k) = s.V.row(s.F(f, k));
      out.F(f, k) = static_cast<int>(3 * f + k);
    }
  return out;
}
}  // namespace

TEST(WeldedView, MergesExactCopiesInTheOrderOfTheirFirstAppearance) {
  Surface s;
  s.V.resize(6, 3);
  s.V << 0, 0, 0,  //
      1, 0, 0,     //
      0, 0, 0,     // a copy of 0
      0, 1, 0,     //
      1, 0, 1e-300,  // close to 1, not equal: stays
      1, 0, 0;     // a copy of 1
  s.F.resize(2, 3);
  s.F << 0, 1, 3,  //
      2, 5, 4;
  const WeldedView v = weld_coincident(s);
  EXPECT_EQ(v.merged(), 2);
  ASSERT_EQ(v.surface.V.rows(), 4);
  EXPECT_EQ(v.view_vertex, (std::vector<int>{0, 1, 0, 2, 3, 1}));
  for (size_t i = 0; i < v.view_vertex.size(); ++i) EXPECT_EQ(v.surface.V.row(v.view_vertex[i]), s.V.row(i)) << i;
  EXPECT_EQ(v.surface.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(v.surface.F.row(1), Eigen::RowVector3i(0, 1, 3));
  // Results on the view come back to every copy.
  const Eigen::VectorXd per_view = Eigen::Vector4d(10, 11, 12, 13);
  EXPECT_EQ(v.to_input(per_view), (Eigen::VectorXd(6) << 10, 11, 10, 12, 13, 11).finished());
}

TEST(WeldedView, PositionsComeBackBitForBitWhereNothingMoved) {
  Surface s;
  s.V.resize(3, 3);
  s.V << -0.0, 0, 0,  //
      0.0, 0, 0,      // equal to -0: the same point, merged
      0, 5, 0;
  s.F.resize(1, 3);
  s.F << 0, 1, 2;
  const WeldedView v = weld_coincident(s);
  ASSERT_EQ(v.merged(), 1);
  Points after = v.surface.V;
  Points back = v.positions_to_input(s.V, after);
  EXPECT_TRUE(std::signbit(back(0, 0)));
  EXPECT_FALSE(std::signbit(back(1, 0)));
  after(0, 2) = 3.0;  // the merged point moves: both copies follow
  back = v.positions_to_input(s.V, after);
  EXPECT_EQ(back.row(0), Eigen::RowVector3d(0, 0, 3));
  EXPECT_EQ(back.row(1), Eigen::RowVector3d(0, 0, 3));
  EXPECT_EQ(back.row(2), s.V.row(2));
}

TEST(WeldedView, LeavesAMeshTheCoreWillRefuseAsItIs) {
  Surface s = test::box({0, 0, 0}, {1, 1, 1});
  s.V.conservativeResize(s.V.rows() + 2, 3);
  s.V.row(s.V.rows() - 2) = s.V.row(0);
  s.V(s.V.rows() - 1, 0) = std::numeric_limits<double>::quiet_NaN();
  WeldedView v = weld_coincident(s);
  EXPECT_EQ(v.merged(), 0);  // a NaN: check_surface must name the input's own vertex
  EXPECT_EQ(v.surface.V.rows(), s.V.rows());
  s.V.conservativeResize(s.V.rows() - 1, 3);
  s.F(0, 0) = 99;  // an index out of range: the same
  v = weld_coincident(s);
  EXPECT_EQ(v.merged(), 0);
  EXPECT_EQ(v.surface.F, s.F);
}

TEST(WeldedView, GivesATriangleSoupItsTopology) {
  // An inside-out box stored as separate triangles: through indices it is 12 open pieces and its
  // orientation says nothing; welded, it is the closed box, and inside out.
  const Surface pieces = soup(flipped(test::box({0, 0, 0}, {10, 10, 10})));
  EXPECT_GT(edge_topology(pieces).open_edges, 0);
  EXPECT_FALSE(inside_out(pieces, edge_topology(pieces)));
  const WeldedView v = weld_coincident(pieces);
  EXPECT_EQ(v.surface.V.rows(), 8);
  EXPECT_EQ(v.merged(), 36 - 8);
  const EdgeTopology edges = edge_topology(v.surface);
  EXPECT_EQ(edges.open_edges, 0);
  EXPECT_TRUE(inside_out(v.surface, edges));
  EXPECT_NE(v.vertex_number_note("edge (3, 7) is open"), "");
  EXPECT_EQ(v.vertex_number_note("the self-supporting angle must be in [0, 90)"), "");
}
