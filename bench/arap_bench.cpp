// The global step and the local step's polar decomposition on box grids of about 1k, 10k and
// 50k vertices (the 50k grid has 280k tets). The speed targets: 50k setup <= 1.5 s and a whole
// iteration <= 80 ms; 10k: setup plus 50 iterations <= 1 s.
//
//   build-*/bench/arap_bench --benchmark_counters_tabular=true
//
// Setup        assembly + factorization (the ArapSolver constructor), plate pinned
// BackSubst    one bare back-substitution, three right-hand sides (SupernodalSolver)
// BackSubstCholmodSolve  the same by CHOLMOD's own solve, for comparison
// Solve        RHS assembly + back-substitution + scatter; counter full/bare = Solve / BackSubst
// Polar*       closest rotation of every tet's Q = V_t (V_t^0)^-1, from a real deformed state
// Iteration    local step (polar, L_t = M_t, OpenMP) + global step
// Run50        setup + 50 iterations
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <chrono>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "core/rotation/polar.h"
#include "core/solver/arap.h"
#include "support/tet_grid.h"

using namespace slim;

namespace {

// n cubes per side: 9 -> 1,000 vertices, 21 -> 10,648, 36 -> 50,653.
struct Case {
  int n = 0;
  TetMesh mesh;
  std::vector<int> pins;
  std::unique_ptr<ArapSolver> solver;
  std::vector<Eigen::Matrix3d> rest_inverse;  // (V_t^0)^-1
  std::vector<Eigen::Matrix3d> L;             // random rotations, up to 0.3 rad
  Points deformed;                            // the solve for L: where the local step starts
  std::vector<Eigen::Matrix3d> Q;             // V_t (V_t^0)^-1 of `deformed`
};

const Case& get_case(int n) {
  static std::map<int, std::unique_ptr<Case>> cache;
  auto& c = cache[n];
  if (c) return *c;
  c = std::make_unique<Case>();
  c->n = n;
  c->mesh = test::tet_grid(n, n, n, 1.0);
  c->pins = test::grid_bottom_vertices(n, n);
  c->solver = std::make_unique<ArapSolver>(c->mesh, c->pins);
  const int nt = static_cast<int>(c->mesh.T.rows());
  std::mt19937_64 gen(1);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(-0.3, 0.3);
  for (int t = 0; t < nt; ++t) {
    c->rest_inverse.push_back(edge_matrix(c->mesh.V, c->mesh.T.row(t)).inverse());
    const Eigen::Vector3d axis(normal(gen), normal(gen), normal(gen));
    c->L.push_back(Eigen::AngleAxisd(angle(gen), axis.normalized()).toRotationMatrix());
  }
  c->deformed = c->solver->solve(c->L, c->mesh.V);
  for (int t = 0; t < nt; ++t)
    c->Q.push_back(edge_matrix(c->deformed, c->mesh.T.row(t)) * c->rest_inverse[static_cast<size_t>(t)]);
  return *c;
}

// The ARAP local step without the support rotation: L_t = polar(V_t (V_t^0)^-1).
void local_step(const Case& c, const Points& V, std::vector<Eigen::Matrix3d>& L) {
  const int nt = static_cast<int>(c.mesh.T.rows());
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t)
    L[static_cast<size_t>(t)] =
        closest_rotation(edge_matrix(V, c.mesh.T.row(t)) * c.rest_inverse[static_cast<size_t>(t)]);
}

void set_size_counters(benchmark::State& state, const Case& c) {
  state.counters["vertices"] = static_cast<double>(c.mesh.V.rows());
  state.counters["tets"] = static_cast<double>(c.mesh.T.rows());
}

void BM_Setup(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    ArapSolver s(c.mesh, c.pins);
    benchmark::DoNotOptimize(s.free_vertices().data());
  }
  set_size_counters(state, c);
  state.SetLabel(c.solver->backend_name());
}

void BM_BackSubst(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd rhs = c.solver->assemble_rhs(c.L, c.mesh.V);
  for (auto _ : state) benchmark::DoNotOptimize(c.solver->back_substitute(rhs).data());
  set_size_counters(state, c);
}

// The global step's three columns and a load's three (volume keeping's pressure) in one sweep.
void BM_BackSubstSix(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd three = c.solver->assemble_rhs(c.L, c.mesh.V);
  Eigen::MatrixXd rhs(three.rows(), 6);
  rhs << three, three.reverse();
  for (auto _ : state) benchmark::DoNotOptimize(c.solver->back_substitute(rhs).data());
  set_size_counters(state, c);
}

// The same back-substitution by CHOLMOD's own supernodal solve, for comparison.
void BM_BackSubstCholmodSolve(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  ArapOptions o;
  o.own_supernodal_solve = false;
  const ArapSolver s(c.mesh, c.pins, o);
  const Eigen::MatrixXd rhs = s.assemble_rhs(c.L, c.mesh.V);
  for (auto _ : state) benchmark::DoNotOptimize(s.back_substitute(rhs).data());
  set_size_counters(state, c);
}

void BM_Rhs(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(c.solver->assemble_rhs(c.L, c.mesh.V).data());
}

// Times both halves inside the same loop, so full/bare compares like with like.
void BM_Solve(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  using clock = std::chrono::steady_clock;
  double bare = 0.0, full = 0.0;
  for (auto _ : state) {
    const auto t0 = clock::now();
    const Eigen::MatrixXd rhs = c.solver->assemble_rhs(c.L, c.mesh.V);
    const auto t1 = clock::now();
    const Eigen::MatrixXd x = c.solver->back_substitute(rhs);
    const auto t2 = clock::now();
    Points V = c.mesh.V;
    for (size_t f = 0; f < c.solver->free_vertices().size(); ++f)
      V.row(c.solver->free_vertices()[f]) = x.row(static_cast<Eigen::Index>(f));
    benchmark::DoNotOptimize(V.data());
    const auto t3 = clock::now();
    bare += std::chrono::duration<double>(t2 - t1).count();
    full += std::chrono::duration<double>(t3 - t0).count();
  }
  state.counters["full/bare"] = full / bare;
  state.counters["rhs_share"] = 1.0 - bare / full;
}

// closest_rotation (scaled Newton, SVD fallback) or closest_rotation_svd (JacobiSVD only).
void BM_Polar(benchmark::State& state, Eigen::Matrix3d (*polar)(const Eigen::Matrix3d&)) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (auto _ : state)
    for (const auto& q : c.Q) sum += polar(q);
  benchmark::DoNotOptimize(sum.data());
  state.counters["tets/s"] =
      benchmark::Counter(static_cast<double>(c.Q.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Iteration(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  std::vector<Eigen::Matrix3d> L(c.L.size());
  for (auto _ : state) {
    local_step(c, c.deformed, L);
    benchmark::DoNotOptimize(c.solver->solve(L, c.deformed).data());
  }
}

void BM_Run50(benchmark::State& state) {
  const Case& c = get_case(static_cast<int>(state.range(0)));
  std::vector<Eigen::Matrix3d> L(c.L.size());
  for (auto _ : state) {
    ArapSolver s(c.mesh, c.pins);
    Points V = c.deformed;
    for (int it = 0; it < 50; ++it) {
      local_step(c, V, L);
      V = s.solve(L, V);
    }
    benchmark::DoNotOptimize(V.data());
  }
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(9)->Arg(21)->Arg(36)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
}

}  // namespace

BENCHMARK(BM_Setup)->Apply(sizes);
BENCHMARK(BM_BackSubst)->Apply(sizes);
BENCHMARK(BM_BackSubstSix)->Apply(sizes);
BENCHMARK(BM_BackSubstCholmodSolve)->Apply(sizes);
BENCHMARK(BM_Rhs)->Apply(sizes);
BENCHMARK(BM_Solve)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Polar, Newton, &closest_rotation)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Polar, JacobiSVD, &closest_rotation_svd)->Apply(sizes);
BENCHMARK(BM_Iteration)->Apply(sizes);
BENCHMARK(BM_Run50)->Arg(21)->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);
