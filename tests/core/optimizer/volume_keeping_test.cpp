// Keeping the volume through the global step (core/optimizer/volume_keeping.h): the pressure's lambda, found
// on the exact cubic, against a brute-force bisection on the embedded surface's own volume, on the
// ball embedded in its voxel domain and bent by random rotations.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/domain/embedded_domain.h"
#include "core/geometry/checked_surface.h"
#include "core/optimizer/volume_keeping.h"
#include "core/platform/parallel_for.h"
#include "core/solver/arap.h"
#include "support/shapes.h"

using namespace slim;

namespace {

double embedded_volume(const Embedding& e, const Triangles& F, const Points& V) {
  Points S;
  embedded_positions(e, V, S);
  return signed_volume(Surface{S, F});
}

// d volume(V) / d V(v, k) by central differences of step 1e-4.
template <class Volume>
double central_slope(const Volume& volume, const Points& V, Eigen::Index v, int k) {
  const double h = 1e-4;
  Points up = V, down = V;
  up(v, k) += h;
  down(v, k) -= h;
  return (volume(up) - volume(down)) / (2 * h);
}

// The volume's gradient as one pass face by face would scatter it (the load's bits are held to
// it): d Vol / d V at the domain vertices, from the embedded surface S.
Points embedded_volume_gradient(const Embedding& e, const Triangles& F, const Points& S, Eigen::Index domain_vertices) {
  const Eigen::RowVector3d centre = S.colwise().mean();
  Points gS = Points::Zero(S.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = (S.row(F(f, 0)) - centre).transpose(), b = (S.row(F(f, 1)) - centre).transpose(),
                          c = (S.row(F(f, 2)) - centre).transpose();
    gS.row(F(f, 0)) += b.cross(c).transpose() / 6.0;
    gS.row(F(f, 1)) += c.cross(a).transpose() / 6.0;
    gS.row(F(f, 2)) += a.cross(b).transpose() / 6.0;
  }
  Points g = Points::Zero(domain_vertices, 3);
  for (Eigen::Index i = 0; i < S.rows(); ++i)
    for (int k = 0; k < 4; ++k) g.row(e.vertex_nodes(i, k)) += e.vertex_bary(i, k) * gS.row(i);
  return g;
}

// Rotations by up to `degrees` about random axes: a global step that squeezes or swells the part.
std::vector<Eigen::Matrix3d> random_turns(int n, double degrees, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> g;
  std::vector<Eigen::Matrix3d> L(static_cast<size_t>(n));
  for (auto& R : L) {
    const Eigen::Vector3d axis = Eigen::Vector3d(g(gen), g(gen), g(gen)).normalized();
    R = test::axis_angle(axis, degrees * M_PI / 180.0 * std::abs(g(gen)) / 3.0);
  }
  return L;
}

// A ball (an icosphere of `levels` subdivisions) resting on z = 0, embedded in its voxel domain at
// `resolution` cells.
struct BallInDomain {
  Surface ball;
  EmbeddedDomain domain;
  explicit BallInDomain(int resolution, int levels = 3) : ball(test::icosphere(levels)) {
    domain = embedded_domain(CheckedSurface(ball), Eigen::Vector3d::UnitZ(), DomainKind::Voxel, resolution, 4e9,
                             [](double, const std::string&) {});
  }
};

}  // namespace

TEST(VolumeKeeping, LambdaOnTheCubicIsTheRootBisectionFinds) {
  const BallInDomain fixture(12);
  const Surface& ball = fixture.ball;
  const EmbeddedDomain& domain = fixture.domain;
  std::vector<int> plate;
  for (Eigen::Index v = 0; v < domain.mesh.V.rows(); ++v)
    if (domain.on_plate(v)) plate.push_back(static_cast<int>(v));
  const ArapSolver arap(domain.mesh, plate);
  const double target = signed_volume(ball);
  for (unsigned seed : {1u, 2u, 3u}) {
    const std::vector<Eigen::Matrix3d> L = random_turns(static_cast<int>(domain.mesh.T.rows()), 20.0, seed);
    Points u;
    const Points solved =
        arap.solve_with_response(L, domain.mesh.V, volume_load(domain.embedding, ball.F, domain.mesh.V), u);
    const double before = embedded_volume(domain.embedding, ball.F, solved);
    ASSERT_GT(std::abs(before / target - 1.0), 1e-3) << "the random step should change the volume";
    Points kept = solved;
    const double lambda = keep_volume(domain.embedding, ball.F, target, u, kept);
    EXPECT_NEAR(embedded_volume(domain.embedding, ball.F, kept), target, 1e-9 * target) << seed;
    EXPECT_TRUE(kept.isApprox(solved + lambda * u, 1e-15)) << seed;
    // Brute force: bisection on the embedded surface's volume along u, from a bracket.
    auto excess = [&](double l) { return embedded_volume(domain.embedding, ball.F, solved + l * u) - target; };
    double lo = 0.0, hi = lambda * 2.0 + (lambda >= 0 ? 1e-12 : -1e-12);
    ASSERT_LT(excess(lo) * excess(hi), 0.0) << seed;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (excess(mid) * excess(lo) > 0.0 ? lo : hi) = mid;
    }
    EXPECT_NEAR(lambda, 0.5 * (lo + hi), 1e-9 * std::abs(lambda)) << seed;
  }
}

// An open surface's volume depends on the point it is taken about (the surface's centroid, which
// moves with the domain): the ball with its top faces cut away, bent at random, is brought back to
// its own volume as signed_volume() measures the embedded surface, its load is that volume's
// gradient, and the domain sums faces within one tet and faces across tets alike.
TEST(VolumeKeeping, AnOpenSurfaceKeepsTheVolumeAboutItsCentroid) {
  const BallInDomain in_domain(8, 5);
  const Surface& ball = in_domain.ball;
  const EmbeddedDomain& domain = in_domain.domain;
  std::vector<int> kept_faces;
  for (Eigen::Index f = 0; f < ball.F.rows(); ++f)
    if (ball.V(ball.F(f, 0), 2) < 0.7 * ball.V.col(2).maxCoeff()) kept_faces.push_back(static_cast<int>(f));
  Triangles open(static_cast<Eigen::Index>(kept_faces.size()), 3);
  int across = 0;
  for (size_t j = 0; j < kept_faces.size(); ++j) {
    open.row(static_cast<Eigen::Index>(j)) = ball.F.row(kept_faces[j]);
    const Eigen::RowVector3i f = ball.F.row(kept_faces[j]);
    const auto& tet = domain.embedding.vertex_tet;
    across += tet(f(0)) != tet(f(1)) || tet(f(1)) != tet(f(2));
  }
  ASSERT_LT(open.rows(), ball.F.rows());
  ASSERT_GT(across, 10);
  ASSERT_LT(across, open.rows() - 10);
  const Points V = domain.mesh.V + 0.05 * Points::Random(domain.mesh.V.rows(), 3);
  const Points u = Points::Random(V.rows(), 3);
  VolumeKeeping volume(domain.embedding, open, V.rows());
  const double target = embedded_volume(domain.embedding, open, domain.mesh.V);
  Points moved = V;
  volume.keep(target, u, moved);
  EXPECT_NEAR(embedded_volume(domain.embedding, open, moved), target, 1e-9 * std::abs(target));
  const Points load = volume.load(V);
  // The load holds the centroid still (the pressure's direction), so compare with the volume
  // about a fixed point: the centroid of the surface at V.
  Points S;
  embedded_positions(domain.embedding, V, S);
  const Eigen::RowVector3d centre = S.colwise().mean();
  auto about_centre = [&](const Points& at) {
    Points moved_surface;
    embedded_positions(domain.embedding, at, moved_surface);
    double vol = 0.0;
    for (Eigen::Index f = 0; f < open.rows(); ++f)
      vol += (moved_surface.row(open(f, 0)) - centre).dot((moved_surface.row(open(f, 1)) - centre).cross(moved_surface.row(open(f, 2)) - centre));
    return vol / 6.0;
  };
  for (Eigen::Index v : {Eigen::Index(0), V.rows() / 3, V.rows() / 2}) {
    const double slope = central_slope(about_centre, V, v, 0);
    EXPECT_NEAR(load(v, 0), slope, 1e-6 * (1.0 + std::abs(slope))) << v;
  }
}

TEST(VolumeKeeping, NoResponseLeavesThePositionsAlone) {
  const BallInDomain fixture(8);
  const Surface& ball = fixture.ball;
  const EmbeddedDomain& domain = fixture.domain;
  Points V = domain.mesh.V * 1.01;
  const Points before = V;
  EXPECT_EQ(keep_volume(domain.embedding, ball.F, signed_volume(ball), Points::Zero(V.rows(), 3), V), 0.0);
  EXPECT_TRUE(V == before);
}

// The set-up sums each group of faces' minors on the threads in face order, and the steps add the
// triples and the faces taken by themselves in order: on a surface large enough for the threads
// (81,920 faces), the load is the face-by-face pass's to rounding (and the volume's gradient, by
// central differences), the same bits on one thread and on two, and so are lambda and the moved
// positions.
TEST(VolumeKeeping, ALargeSurfaceGivesTheOnePassLoadAndTheSameLambdaOnAnyThreadCount) {
  const BallInDomain in_domain(10, 6);
  const Surface& ball = in_domain.ball;
  const EmbeddedDomain& domain = in_domain.domain;
  const Points V = domain.mesh.V + 0.3 * Points::Random(domain.mesh.V.rows(), 3);
  Points S;
  embedded_positions(domain.embedding, V, S);
  const Points reference = embedded_volume_gradient(domain.embedding, ball.F, S, V.rows());
  const Points u = Points::Random(V.rows(), 3);
  std::vector<double> lambdas;
  std::vector<Points> kept, loads;
  for (int threads : {1, 2}) {
    const ThreadScope scope(threads);
    VolumeKeeping volume(domain.embedding, ball.F, V.rows());
    loads.push_back(volume.load(V));
    EXPECT_LE((loads.back() - reference).cwiseAbs().maxCoeff(), 1e-12 * reference.cwiseAbs().maxCoeff()) << threads;
    Points moved = V;
    lambdas.push_back(volume.keep(signed_volume(ball), u, moved));
    kept.push_back(moved);
  }
  EXPECT_TRUE(loads[0] == loads[1]);
  EXPECT_EQ(lambdas[0], lambdas[1]);
  EXPECT_TRUE(kept[0] == kept[1]);
  EXPECT_NEAR(embedded_volume(domain.embedding, ball.F, kept[0]), signed_volume(ball), 1e-9 * signed_volume(ball));
  auto volume_at = [&](const Points& at) { return embedded_volume(domain.embedding, ball.F, at); };
  for (Eigen::Index v : {Eigen::Index(0), V.rows() / 2, V.rows() - 1})
    for (int k = 0; k < 3; ++k) {
      const double slope = central_slope(volume_at, V, v, k);
      EXPECT_NEAR(reference(v, k), slope, 1e-6 * (1.0 + std::abs(slope))) << v << " " << k;
    }
}

TEST(VolumeKeeping, FacesOutsideTheEmbeddingAreRefused) {
  const BallInDomain fixture(8);
  Triangles bad = fixture.ball.F;
  bad(0, 0) = static_cast<int>(fixture.ball.V.rows());
  EXPECT_THROW(VolumeKeeping(fixture.domain.embedding, bad, fixture.domain.mesh.V.rows()), std::invalid_argument);
  EXPECT_THROW(VolumeKeeping(fixture.domain.embedding, fixture.ball.F, 3), std::invalid_argument);
}
