// Voxel domain + embedding: the sample bunny at 32, 64 and 128 cells, and a 1.3M-face sphere
// (icosphere level 8) at 64 cells. Target for the big mesh: <= 1 s and <= 1.5 GB.
//
// Peak memory: run one case alone and read the VmHWM counter (the process's high-water mark,
// which includes building the input mesh), e.g.
//   domain_bench --benchmark_filter=Sphere
#include <benchmark/benchmark.h>

#include <fstream>
#include <string>

#include "core/domain/embedding.h"
#include "core/domain/voxel_domain.h"
#include "support/shapes.h"

namespace {

double peak_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

void run(benchmark::State& state, const slim::Surface& s) {
  slim::VoxelDomainOptions options;
  options.resolution = static_cast<int>(state.range(0));
  slim::VoxelDomain dom;
  slim::Embedding e;
  for (auto _ : state) {
    dom = slim::voxel_domain(s, Eigen::Vector3d::UnitZ(), options);
    e = slim::embed_surface(s, dom);
    benchmark::DoNotOptimize(e.tet_faces.data());
  }
  state.counters["faces"] = static_cast<double>(s.F.rows());
  state.counters["domain_vertices"] = static_cast<double>(dom.mesh.V.rows());
  state.counters["tets"] = static_cast<double>(dom.mesh.T.rows());
  state.counters["split_faces"] = static_cast<double>(e.split_faces);
  state.counters["VmHWM_MB"] = peak_rss_mb();
}

#ifdef SLIM_TESTS_HAVE_VCG
void Bunny(benchmark::State& state) {
  static const slim::Surface bunny = slim::test::load_mesh(slim::test::sample_bunny_path());
  run(state, bunny);
}
BENCHMARK(Bunny)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
#endif

void Sphere1M(benchmark::State& state) {
  static const slim::Surface sphere = slim::test::icosphere(8);  // 1,310,720 faces
  run(state, sphere);
}
BENCHMARK(Sphere1M)->Arg(64)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
