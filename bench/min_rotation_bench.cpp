// Time per slim::min_rotation call on realistic risky patches, tau = sin 45°, d = +Z.
//   Clustered: normals within 40° of a random downward direction (one tet's worth of a curved
//              underside); a fresh patch each call, cycling through 64 of them.
//   LowerHemisphere: normals uniform on the lower hemisphere (a worst case: wide, mostly risky).
//   Tight:     normals within 1° of a random downward direction (a tet of a scan with a hundred
//              faces or more: their hull is too nearly degenerate to trust).
//   FloatGroups: Tight's directions within 5°, each repeated 4 times 1e-5 apart (a tet of a dense
//              subdivided mesh whose vertices were stored as floats: a face's four pieces).
// Run: build/bench/min_rotation_bench  (medians of 5 repetitions are printed).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/rotation/min_rotation.h"
#include "support/min_rotation_reference.h"

namespace {

const double kTau = std::sin(M_PI / 4);
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

std::vector<Eigen::Matrix3Xd> patches(int n, double spread_deg, bool clustered, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Eigen::Matrix3Xd> all;
  for (int k = 0; k < 64; ++k) {
    const Eigen::Vector3d down = slim::test::random_in_cap(rng, -kUp, M_PI / 2);
    all.push_back(clustered ? slim::test::random_normals_in_cap(rng, n, down, spread_deg * M_PI / 180)
                            : slim::test::random_normals_in_cap(rng, n, -kUp, M_PI / 2));
  }
  return all;
}

// Each normal of `all` repeated `copies` times, each copy moved by 1e-5 radians.
std::vector<Eigen::Matrix3Xd> in_groups(const std::vector<Eigen::Matrix3Xd>& all, int copies) {
  std::mt19937 rng(7);
  std::vector<Eigen::Matrix3Xd> out;
  for (const Eigen::Matrix3Xd& patch : all) {
    Eigen::Matrix3Xd grouped(3, patch.cols());
    for (Eigen::Index i = 0; i < patch.cols(); ++i) grouped.col(i) = slim::test::random_in_cap(rng, patch.col(i / copies), 1e-6);
    out.push_back(grouped);
  }
  return out;
}

void run(benchmark::State& state, bool clustered, double spread_deg = 40.0, int copies = 1) {
  std::vector<Eigen::Matrix3Xd> all = patches(static_cast<int>(state.range(0)), spread_deg, clustered, 42);
  if (copies > 1) all = in_groups(all, copies);
  size_t k = 0, feasible = 0;
  for (auto _ : state) {
    const slim::MinRotation r = slim::min_rotation(all[k++ % all.size()], kUp, kTau);
    feasible += r.feasible;
    benchmark::DoNotOptimize(r);
  }
  state.counters["feasible_share"] = static_cast<double>(feasible) / static_cast<double>(k);
}

void Clustered(benchmark::State& state) { run(state, true); }
void LowerHemisphere(benchmark::State& state) { run(state, false); }
void Tight(benchmark::State& state) { run(state, true, 1.0); }
void FloatGroups(benchmark::State& state) { run(state, true, 30.0, 16); }

}  // namespace

BENCHMARK(Clustered)->RangeMultiplier(4)->Range(4, 1024)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(LowerHemisphere)->RangeMultiplier(4)->Range(4, 1024)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(Tight)->RangeMultiplier(4)->Range(64, 1024)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(FloatGroups)->RangeMultiplier(4)->Range(64, 1024)->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
