// The global step: known answers (rest, rigid motions), the minimiser property checked against
// an independent gradient, held vertices, factor-once, backends, determinism and errors.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/solver/arap.h"
#include "support/arap_reference.h"
#include "support/tet_grid.h"

using namespace slim;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Backend = ArapOptions::Backend;

namespace {

// A 4 x 3 x 5 box of 2 mm cubes, off the origin so that nothing relies on a zero corner.
constexpr int kNx = 4, kNy = 3, kNz = 5;
TetMesh small_grid() { return test::tet_grid(kNx, kNy, kNz, 2.0, Vector3d(1.0, -3.0, 0.5)); }
std::vector<int> plate() { return test::grid_bottom_vertices(kNx, kNy); }

Matrix3d random_rotation(std::mt19937_64& gen, double max_angle) {
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> u(-max_angle, max_angle);
  return Eigen::AngleAxisd(u(gen), Vector3d(n(gen), n(gen), n(gen)).normalized()).toRotationMatrix();
}

std::vector<Matrix3d> random_rotations(int count, unsigned seed, double max_angle = 0.6) {
  std::mt19937_64 gen(seed);
  std::vector<Matrix3d> L;
  for (int t = 0; t < count; ++t) L.push_back(random_rotation(gen, max_angle));
  return L;
}

Points rigidly_moved(const Points& V, const Matrix3d& R, const Vector3d& shift) {
  return ((V * R.transpose()).rowwise() + shift.transpose()).eval();
}

Points energy_gradient(const TetMesh& rest, const Points& V, const std::vector<Matrix3d>& L) {
  return test::arap_energy_gradient(rest, V, L);
}

double max_free_row_norm(const Points& g, const ArapSolver& s) {
  double m = 0.0;
  for (int v : s.free_vertices()) m = std::max(m, g.row(v).norm());
  return m;
}

}  // namespace

TEST(TetGrid, ConformingPositiveKuhnSplit) {
  const TetMesh m = small_grid();
  ASSERT_EQ(m.V.rows(), (kNx + 1) * (kNy + 1) * (kNz + 1));
  ASSERT_EQ(m.T.rows(), 6 * kNx * kNy * kNz);
  double total = 0.0;
  for (int t = 0; t < m.T.rows(); ++t) {
    EXPECT_NEAR(tet_volume(m.V, m.T.row(t)), 8.0 / 6.0, 1e-12);
    total += tet_volume(m.V, m.T.row(t));
  }
  EXPECT_NEAR(total, 8.0 * kNx * kNy * kNz, 1e-9);
  for (int v : plate()) EXPECT_EQ(m.V(v, 2), 0.5);
}

TEST(Arap, IdentityMapsKeepTheRestShape) {
  const TetMesh m = small_grid();
  const ArapSolver s(m, plate());
  EXPECT_EQ(static_cast<int>(s.free_vertices().size()), m.V.rows() - static_cast<Eigen::Index>(plate().size()));
  const std::vector<Matrix3d> I(static_cast<size_t>(m.T.rows()), Matrix3d::Identity());
  EXPECT_LE((s.solve(I, m.V) - m.V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE(s.energy(m.V, I), 1e-20);
}

TEST(Arap, RigidMotionAboutOnePinnedVertex) {
  const TetMesh m = small_grid();
  const int pivot = 37;
  const ArapSolver s(m, {pivot});
  std::mt19937_64 gen(3);
  for (int k = 0; k < 5; ++k) {
    const Matrix3d R = random_rotation(gen, 3.0);
    const Vector3d p = m.V.row(pivot).transpose();
    const Points expected = rigidly_moved(m.V, R, p - R * p);
    const std::vector<Matrix3d> L(static_cast<size_t>(m.T.rows()), R);
    const Points V = s.solve(L, m.V);
    EXPECT_LE((V - expected).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LE(s.energy(V, L), 1e-18);
  }
}

// Held positions need not be the rest ones: a plate moved rigidly with L = R moves everything.
TEST(Arap, RigidMotionOfThePinnedPlate) {
  const TetMesh m = small_grid();
  const ArapSolver s(m, plate());
  std::mt19937_64 gen(4);
  const Matrix3d R = random_rotation(gen, 3.0);
  const Points expected = rigidly_moved(m.V, R, Vector3d(5.0, -2.0, 7.0));
  const std::vector<Matrix3d> L(static_cast<size_t>(m.T.rows()), R);
  EXPECT_LE((s.solve(L, expected) - expected).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Arap, SolutionMinimisesTheEnergy) {
  const TetMesh m = small_grid();
  const ArapSolver s(m, plate());
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 11);
  const Points V = s.solve(L, m.V);
  const double e = s.energy(V, L);
  EXPECT_LT(e, s.energy(m.V, L));

  // Zero gradient on the free vertices, relative to the gradient at the start.
  const double g0 = max_free_row_norm(energy_gradient(m, m.V, L), s);
  ASSERT_GT(g0, 1.0);
  EXPECT_LE(max_free_row_norm(energy_gradient(m, V, L), s), 1e-10 * g0);

  // Any change of the free vertices raises E (the plate is held).
  std::mt19937_64 gen(12);
  std::normal_distribution<double> n;
  for (double size : {1e-3, 1e-1, 1.0}) {
    Points P = V;
    for (int v : s.free_vertices())
      for (int c = 0; c < 3; ++c) P(v, c) += size * n(gen);
    EXPECT_GT(s.energy(P, L), e) << size;
  }
}

// energy() agrees with the independent gradient by central differences, so the two above
// check the same objective.
TEST(Arap, EnergyMatchesItsGradient) {
  const TetMesh m = small_grid();
  const ArapSolver s(m, plate());
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 13);
  const Points g = energy_gradient(m, m.V, L);
  const double h = 1e-5;
  for (int v : {0, 40, 77, 119}) {
    for (int c = 0; c < 3; ++c) {
      Points plus = m.V, minus = m.V;
      plus(v, c) += h;
      minus(v, c) -= h;
      const double fd = (s.energy(plus, L) - s.energy(minus, L)) / (2 * h);
      EXPECT_NEAR(fd, g(v, c), 1e-6 * (1.0 + std::abs(g(v, c))));
    }
  }
}

TEST(Arap, HeldVerticesAreExactlyWhereGiven) {
  const TetMesh m = small_grid();
  const ArapSolver s(m, plate());
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 21);
  std::mt19937_64 gen(22);
  std::normal_distribution<double> n;
  Points held = m.V;
  for (int v : plate())
    for (int c = 0; c < 3; ++c) held(v, c) += n(gen);
  const Points V = s.solve(L, held);
  for (int v : plate()) EXPECT_EQ(V.row(v), held.row(v));
  // Only the held rows of V_held are read.
  Points other = held;
  for (int v : s.free_vertices()) other.row(v).setConstant(1e6);
  EXPECT_EQ(s.solve(L, other), V);
}

TEST(Arap, FactorsOnceAndMatchesFreshSolvers) {
  const TetMesh m = small_grid();
  const ArapSolver s(m, plate());
  const std::vector<Matrix3d> L1 = random_rotations(static_cast<int>(m.T.rows()), 31);
  const std::vector<Matrix3d> L2 = random_rotations(static_cast<int>(m.T.rows()), 32);
  const Points V1 = s.solve(L1, m.V), V2 = s.solve(L2, m.V);
  EXPECT_EQ(s.factorizations(), 1);
  EXPECT_EQ(V1, ArapSolver(m, plate()).solve(L1, m.V));
  EXPECT_EQ(V2, ArapSolver(m, plate()).solve(L2, m.V));
  EXPECT_GT((V1 - V2).cwiseAbs().maxCoeff(), 1e-3);  // the two solves really differ
  // solve = back_substitute(assemble_rhs), scattered.
  const Eigen::MatrixXd x = s.back_substitute(s.assemble_rhs(L1, m.V));
  for (size_t f = 0; f < s.free_vertices().size(); ++f)
    EXPECT_EQ(x.row(static_cast<Eigen::Index>(f)), V1.row(s.free_vertices()[f]));
}

// Volume keeping solves the global step and its pressure's response in one sweep of the factor:
// the same bits as the two solves apart (CHOLMOD's own solve, through BLAS, to 1e-12).
TEST(Arap, SolveWithResponseGivesTheBitsOfSolveAndResponse) {
  const TetMesh m = test::tet_grid(9, 8, 7, 1.5);
  const std::vector<int> pins = test::grid_bottom_vertices(9, 8);
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 33);
  const Points load = Points::Random(m.V.rows(), 3);
  std::vector<ArapOptions> options(1);
  if (ArapSolver::cholmod_available()) {
    options.resize(3);
    options[0].backend = Backend::Cholmod;
    options[1].backend = Backend::Cholmod;
    options[1].own_supernodal_solve = false;
  }
  options.back().backend = Backend::EigenLDLT;
  for (const ArapOptions& o : options) {
    const ArapSolver s(m, pins, o);
    Points response;
    const Points V = s.solve_with_response(L, m.V, load, response);
    const Points apart = s.solve(L, m.V), response_apart = s.response(load);
    if (o.own_supernodal_solve || o.backend == Backend::EigenLDLT) {
      EXPECT_TRUE(V == apart) << s.backend_name();
      EXPECT_TRUE(response == response_apart) << s.backend_name();
    } else {
      EXPECT_LE((V - apart).cwiseAbs().maxCoeff(), 1e-12 * apart.cwiseAbs().maxCoeff()) << s.backend_name();
      EXPECT_LE((response - response_apart).cwiseAbs().maxCoeff(), 1e-12 * response_apart.cwiseAbs().maxCoeff());
    }
    EXPECT_GT(response.cwiseAbs().maxCoeff(), 0.0);
    for (int v : pins) EXPECT_TRUE(response.row(v).isZero(0.0) && V.row(v) == m.V.row(v));
  }
}

TEST(Arap, CustomWeightsScaleTheEnergyNotTheMinimiser) {
  const TetMesh m = small_grid();
  const ArapSolver by_volume(m, plate());
  const ArapSolver scaled(m, Eigen::VectorXd::Constant(m.T.rows(), 7.0 * 8.0 / 6.0), plate());
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 41);
  const Points V = by_volume.solve(L, m.V);
  EXPECT_LE((scaled.solve(L, m.V) - V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(scaled.energy(V, L), 7.0 * by_volume.energy(V, L), 1e-9 * by_volume.energy(V, L));
}

TEST(Arap, BackendsAgree) {
  if (!ArapSolver::cholmod_available()) GTEST_SKIP() << "built without CHOLMOD";
  const TetMesh m = test::tet_grid(8, 7, 6, 1.5);
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 51);
  ArapOptions o;
  o.backend = Backend::EigenLDLT;
  const ArapSolver eigen(m, test::grid_bottom_vertices(8, 7), o);
  EXPECT_EQ(eigen.backend_name(), "Eigen SimplicialLDLT");
  const Points reference = eigen.solve(L, m.V);
  for (Backend b : {Backend::Auto, Backend::Cholmod, Backend::CholmodSimplicial}) {
    o.backend = b;
    const ArapSolver s(m, test::grid_bottom_vertices(8, 7), o);
    EXPECT_NE(s.backend_name().find("CHOLMOD"), std::string::npos);
    EXPECT_LE((s.solve(L, m.V) - reference).cwiseAbs().maxCoeff(), 1e-9) << s.backend_name();
  }
  // The supernodal factor solved by CHOLMOD itself rather than by SupernodalSolver.
  o.backend = Backend::Cholmod;
  o.own_supernodal_solve = false;
  const ArapSolver cholmod_solve(m, test::grid_bottom_vertices(8, 7), o);
  EXPECT_LE((cholmod_solve.solve(L, m.V) - reference).cwiseAbs().maxCoeff(), 1e-9);
}

// Large enough (5k free vertices, 28k tets) for OpenMP to split the RHS and the energy.
TEST(Arap, BitwiseRepeatableAcrossRunsAndThreadCounts) {
  const TetMesh m = test::tet_grid(17, 17, 16, 1.0);
  const std::vector<int> pins = test::grid_bottom_vertices(17, 17);
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 61);
  const ArapSolver s(m, pins);
  const Points V = s.solve(L, m.V);
  EXPECT_EQ(s.solve(L, m.V), V);
  EXPECT_EQ(ArapSolver(m, pins).solve(L, m.V), V);
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    EXPECT_EQ(s.assemble_rhs(L, m.V), s.assemble_rhs(L, m.V)) << threads;
    EXPECT_EQ(s.solve(L, m.V), V) << threads;
    EXPECT_EQ(s.energy(V, L), s.energy(V, L)) << threads;
  }
  omp_set_num_threads(1);
  const double e1 = s.energy(V, L);
  omp_set_num_threads(2);
  EXPECT_EQ(s.energy(V, L), e1);
  omp_set_num_threads(before);
#endif
}

// OpenBLAS gives different bits for 1 and 2 threads even on this 2k-vertex system (measured),
// so the solver pins BLAS to ArapOptions::blas_threads: the process's setting must not matter.
TEST(Arap, BitwiseIndependentOfTheProcessBlasThreadCount) {
  using Get = int (*)();
  using Set = void (*)(int);
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (!get || !set) GTEST_SKIP() << "the BLAS in use is not OpenBLAS";
  const int before = get();
  const TetMesh m = test::tet_grid(12, 12, 12, 1.0);
  const std::vector<int> pins = test::grid_bottom_vertices(12, 12);
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 62);
  set(1);
  const Points V1 = ArapSolver(m, pins).solve(L, m.V);
  set(2);
  const ArapSolver s(m, pins);
  EXPECT_EQ(s.solve(L, m.V), V1);
  EXPECT_EQ(get(), 2);  // restored after each call
  set(before);
}

TEST(Arap, VerticesInNoTetAreHeld) {
  TetMesh m = small_grid();
  m.V.conservativeResize(m.V.rows() + 1, 3);
  m.V.row(m.V.rows() - 1) << 100, 100, 100;
  const ArapSolver s(m, plate());
  ASSERT_EQ(s.held_vertices().back(), m.V.rows() - 1);
  Points held = m.V;
  held.row(m.V.rows() - 1) << -5, 6, 7;
  const std::vector<Matrix3d> L = random_rotations(static_cast<int>(m.T.rows()), 71);
  EXPECT_EQ(s.solve(L, held).row(m.V.rows() - 1), held.row(m.V.rows() - 1));
}

// Two separate boxes, only the first pinned: the second is undetermined unless anchored.
TEST(Arap, FloatingComponentThrowsUnlessAnchored) {
  const TetMesh a = test::tet_grid(2, 2, 2, 1.0), b = test::tet_grid(2, 2, 2, 1.0, Vector3d(5, 0, 3));
  TetMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.T.resize(a.T.rows() + b.T.rows(), 4);
  m.T << a.T, (b.T.array() + static_cast<int>(a.V.rows())).matrix();
  const std::vector<int> pins = test::grid_bottom_vertices(2, 2);
  EXPECT_THROW(ArapSolver(m, pins), std::invalid_argument);

  ArapOptions o;
  o.anchor_floating_components = true;
  const ArapSolver s(m, pins, o);
  const int anchor = static_cast<int>(a.V.rows());  // the component's lowest index
  EXPECT_EQ(s.held_vertices().back(), anchor);
  // With L = I the floating box is rebuilt rigidly about its anchor, wherever V_held puts it.
  Points held = m.V;
  held.row(anchor) += Eigen::RowVector3d(1, 2, 3);
  const std::vector<Matrix3d> I(static_cast<size_t>(m.T.rows()), Matrix3d::Identity());
  const Points V = s.solve(I, held);
  EXPECT_LE((V.bottomRows(b.V.rows()).rowwise() - Eigen::RowVector3d(1, 2, 3) - b.V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((V.topRows(a.V.rows()) - a.V).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Arap, BadInputThrowsReadableErrors) {
  const TetMesh m = small_grid();
  EXPECT_THROW(ArapSolver(m, {}), std::invalid_argument);                 // nothing pinned
  EXPECT_THROW(ArapSolver(m, {-1}), std::invalid_argument);               // index out of range
  EXPECT_THROW(ArapSolver(m, {static_cast<int>(m.V.rows())}), std::invalid_argument);
  EXPECT_THROW(ArapSolver(m, Eigen::VectorXd::Ones(3), plate()), std::invalid_argument);  // #weights
  Eigen::VectorXd w = Eigen::VectorXd::Ones(m.T.rows());
  w(5) = -1.0;
  EXPECT_THROW(ArapSolver(m, w, plate()), std::invalid_argument);
  w(5) = NAN;
  EXPECT_THROW(ArapSolver(m, w, plate()), std::invalid_argument);

  TetMesh flat = m;  // tet 0 squashed onto a plane: zero volume
  flat.V.row(flat.T(0, 3)) = (flat.V.row(flat.T(0, 0)) + flat.V.row(flat.T(0, 1))) / 2.0;
  try {
    ArapSolver bad(flat, plate());
    ADD_FAILURE() << "a zero-volume tet was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
  TetMesh inverted = m;
  std::swap(inverted.T(3, 1), inverted.T(3, 2));
  EXPECT_THROW(ArapSolver(inverted, plate()), std::invalid_argument);

  const ArapSolver s(m, plate());
  std::vector<Matrix3d> L(static_cast<size_t>(m.T.rows()), Matrix3d::Identity());
  EXPECT_THROW(s.solve(std::vector<Matrix3d>(3, Matrix3d::Identity()), m.V), std::invalid_argument);
  EXPECT_THROW(s.solve(L, m.V.topRows(5)), std::invalid_argument);
  EXPECT_THROW(s.back_substitute(Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
  L[7](0, 0) = NAN;
  EXPECT_THROW(s.solve(L, m.V), std::runtime_error);
}

TEST(Arap, NoSilentBackendSwitch) {
  // Asking for CHOLMOD gives CHOLMOD when it is built in, and an error (never a quiet fallback to
  // Eigen) when it is not; Auto names what it chose.
  for (Backend b : {Backend::Cholmod, Backend::CholmodSimplicial}) {
    ArapOptions o;
    o.backend = b;
    if (ArapSolver::cholmod_available())
      EXPECT_NE(ArapSolver(small_grid(), plate(), o).backend_name().find("CHOLMOD"), std::string::npos);
    else
      EXPECT_THROW(ArapSolver(small_grid(), plate(), o), std::invalid_argument);
  }
  const std::string chosen = ArapSolver(small_grid(), plate()).backend_name();
  EXPECT_NE(chosen.find(ArapSolver::cholmod_available() ? "CHOLMOD" : "Eigen"), std::string::npos) << chosen;
}
