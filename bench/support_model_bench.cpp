// Time and memory of one support estimate (slim::estimate_support, core/support_model/support_model.h).
//   Bunny/L:        the sample bunny at a 60 mm longest side (as it is printed), refined L times
//                   (each level 4x the faces: 3,674 at L = 0, 940,544 at L = 4); one thread.
//   Bunny2Threads/L: the same on two threads (the grid phases run in parallel).
//   Phases/N:       the bunny (L = 0) with N grid phases (1, 4 = the default, 16); one thread.
// Counters: faces; pixel (mm) and cells × layers swept; extra_MB, the estimate's peak memory above
// the process's (a child process runs one estimate; its peak resident size less that of an idle
// child). Run: build/bench/support_model_bench  (medians of 5 repetitions are printed).
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/support_model/support_model.h"
#include "support/shapes.h"

namespace {

const slim::Surface& bunny(int levels) {
  static slim::Surface cached[5];
  if (cached[levels].F.rows() == 0) {
    slim::Surface base = slim::test::load_mesh(slim::test::sample_bunny_path());
    const Eigen::RowVector3d extent = base.V.colwise().maxCoeff() - base.V.colwise().minCoeff();
    base.V *= 60.0 / extent.maxCoeff();
    cached[levels] = levels == 0 ? base : slim::test::refined(base, levels);
  }
  return cached[levels];
}

// Peak resident size (MB) of a child process that runs `work` once.
template <class Work>
double child_peak_mb(Work work) {
  const pid_t pid = fork();
  if (pid == 0) {
    work();
    _exit(0);
  }
  int status = 0;
  rusage usage{};
  if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return -1.0;
  return usage.ru_maxrss / 1024.0;
}

void estimate(benchmark::State& state, const slim::Surface& s, slim::SupportModelOptions o) {
  slim::SupportEstimate e;
  for (auto _ : state) {
    e = slim::estimate_support(s, o);
    benchmark::DoNotOptimize(e);
  }
  state.counters["faces"] = static_cast<double>(s.F.rows());
  state.counters["pixel_mm"] = e.pixel_mm;
  state.counters["cells_x_layers"] = static_cast<double>(e.cells) * e.layers;
  state.counters["volume_mm3"] = e.volume_mm3;
  o.threads = 1;
  const double idle = child_peak_mb([] {});
  state.counters["extra_MB"] = child_peak_mb([&] { benchmark::DoNotOptimize(slim::estimate_support(s, o)); }) - idle;
}

void Bunny(benchmark::State& state) {
  slim::SupportModelOptions o;
  o.threads = 1;
  estimate(state, bunny(static_cast<int>(state.range(0))), o);
}
void Bunny2Threads(benchmark::State& state) {
  slim::SupportModelOptions o;
  o.threads = 2;
  estimate(state, bunny(static_cast<int>(state.range(0))), o);
}
void Phases(benchmark::State& state) {
  slim::SupportModelOptions o;
  o.threads = 1;
  o.grid_phases = static_cast<int>(state.range(0));
  estimate(state, bunny(0), o);
}

}  // namespace

BENCHMARK(Bunny)->DenseRange(0, 4)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Bunny2Threads)->Arg(0)->Arg(4)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Phases)->Arg(1)->Arg(4)->Arg(16)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
