// --colour: what the output's colours say. With the default (moved), a mesh without vertex colours
// of its own comes back with each vertex's displacement as its quality and as a colour on the
// blue (unmoved) -> red (the budget) ramp; risky colours only the faces; none adds nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "cli_run.h"
#include "mesh_io/mesh_io.h"
#include "support/shapes.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

// Where an RGB colour lies on the ramp blue (0) -> cyan -> green -> yellow -> red (1), read from
// the colour alone; -1 for a colour off the ramp.
double ramp_position(const Eigen::Matrix<unsigned char, 1, 4>& c) {
  const double r = c(0) / 255.0, g = c(1) / 255.0, b = c(2) / 255.0;
  auto full = [](double x) { return x > 0.99; };
  auto zero = [](double x) { return x < 0.01; };  // bytes round: a channel at its end may be off by one
  if (zero(r) && full(b)) return 0.25 * g;
  if (zero(r) && full(g)) return 0.25 + 0.25 * (1 - b);
  if (zero(b) && full(g)) return 0.5 + 0.25 * r;
  if (zero(b) && full(r)) return 0.75 + 0.25 * (1 - g);
  return -1;
}

}  // namespace

TEST(CliColour, TheDefaultColoursEachVertexByHowFarItMoved) {
  const fs::path dir = test::scratch();
  const fs::path out = dir / "moved.ply";
  const Surface in = test::sample_bunny();
  const test::CliRun r = test::run_cli("'" + test::sample_bunny_path() + "' -o '" + out.string() + "' --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::MeshFile back = io::read_mesh(out.string());
  const Eigen::VectorXd moved = (back.surface.V - in.V).rowwise().norm();
  ASSERT_GT(moved.maxCoeff(), 0.0);
  ASSERT_EQ(back.vertex.quality.size(), in.V.rows());
  EXPECT_LT((back.vertex.quality - moved).cwiseAbs().maxCoeff(), 1e-9);  // the displacement, mm
  ASSERT_EQ(back.vertex.colour.rows(), in.V.rows());
  const double budget = 0.05 * test::bbox_diagonal(in);  // the default budget, 5% of the diagonal
  for (Eigen::Index i = 0; i < moved.size(); ++i) {
    const double at = ramp_position(back.vertex.colour.row(i));
    ASSERT_GE(at, 0.0) << i << ": " << back.vertex.colour.row(i).cast<int>();
    ASSERT_NEAR(at, std::min(moved(i) / budget, 1.0), 0.01) << i << ": " << moved(i) << " mm";
  }
  EXPECT_EQ(back.face.colour.rows(), in.F.rows());  // and the faces still say which stay risky
  fs::remove_all(dir);
}

TEST(CliColour, RiskyColoursTheFacesAloneAndNoneAddsNothing) {
  const fs::path dir = test::scratch();
  const std::string bunny = "'" + test::sample_bunny_path() + "' --iterations 2 --quiet -o '";
  ASSERT_EQ(test::run_cli(bunny + (dir / "risky.ply").string() + "' --colour risky").exit_code, 0);
  ASSERT_EQ(test::run_cli(bunny + (dir / "none.ply").string() + "' --colour none").exit_code, 0);
  const io::MeshFile risky = io::read_mesh((dir / "risky.ply").string()), none = io::read_mesh((dir / "none.ply").string());
  EXPECT_EQ(risky.vertex.colour.rows(), 0);
  EXPECT_EQ(risky.vertex.quality.size(), 0);
  EXPECT_EQ(risky.face.colour.rows(), risky.surface.F.rows());
  EXPECT_EQ(none.vertex.colour.rows(), 0);
  EXPECT_EQ(none.face.colour.rows(), 0);
  EXPECT_EQ(none.face.quality.size(), 0);
  EXPECT_EQ(none.face.selected.size(), static_cast<size_t>(none.surface.F.rows()));  // the selection is no colour
  const test::CliRun bad = test::run_cli(bunny + (dir / "x.ply").string() + "' --colour loud");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--colour expects moved, risky or none, got 'loud'"), std::string::npos) << bad.err;
  fs::remove_all(dir);
}
