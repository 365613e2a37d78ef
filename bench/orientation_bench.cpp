// Time of one whole print-orientation search (slim::optimize_orientation, default Normal effort:
// about 5200 directions scored, refinement included) on one core unless stated.
//   Bunny/L: the sample bunny (3,674 faces) refined L times (each level 4x the faces; level 4 is
//            940,544 faces). Refining splits flat, so the normals keep the bunny's 3,674 values.
//   Sphere/L: an icosphere of 20 * 4^L faces, the worst case: every vertex lies on the convex
//            hull and every normal differs.
//   Bunny2Threads/L: as Bunny, on two threads.
// Run: build/bench/orientation_bench  (medians of 5 repetitions are printed).
#include <benchmark/benchmark.h>

#include "core/orientation/orientation.h"
#include "support/shapes.h"

namespace {

const slim::Surface& bunny(int levels) {
  static const slim::Surface base = slim::test::load_mesh(slim::test::sample_bunny_path());
  static slim::Surface cached[5];
  if (cached[levels].F.rows() == 0) cached[levels] = levels == 0 ? base : slim::test::refined(base, levels);
  return cached[levels];
}

void search(benchmark::State& state, const slim::Surface& s, int threads) {
  slim::OrientationOptions o;
  o.threads = threads;
  slim::OrientationResult r;
  for (auto _ : state) {
    r = slim::optimize_orientation(s, o);
    benchmark::DoNotOptimize(r);
  }
  state.counters["faces"] = static_cast<double>(s.F.rows());
  state.counters["directions"] = r.candidates;
  state.counters["hull_facets"] = r.hull_facets;
}

void Bunny(benchmark::State& state) { search(state, bunny(static_cast<int>(state.range(0))), 1); }
void Bunny2Threads(benchmark::State& state) { search(state, bunny(static_cast<int>(state.range(0))), 2); }
void Sphere(benchmark::State& state) {
  static const slim::Surface spheres[] = {slim::test::icosphere(6, 20.0), slim::test::icosphere(7, 20.0)};
  search(state, spheres[state.range(0) - 6], 1);
}

}  // namespace

BENCHMARK(Bunny)->DenseRange(0, 4)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Bunny2Threads)->Arg(4)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Sphere)->DenseRange(6, 7)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
