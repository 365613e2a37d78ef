// Per-stage times of Support Slimming on voxel domains of about 1k, 10k and 50k vertices (the
// sample bunny at three resolutions), medians over repeated runs, and the ratio of one whole
// iteration to one bare back-substitution of the same factor, measured in the same run.
// --end-to-end F: then one whole run at the defaults (budget, stopping rule, the support model's
// choice) on the bunny refined until it has at least F faces (4 levels: 940,544), stage by stage.
// Refinement splits each triangle in four in its own plane, so the faces of one original triangle
// share a normal (to the last bits), which the local step merges; a scan has no such faces:
// --jitter MM moves every vertex of the refined bunny by up to MM (a fixed seed), so none do.
// --mesh PATH: the end-to-end run refines that mesh instead (data/corpus/bunny_70k.ply refined
// twice: the 1,114,656-face bunny of the large-mesh speed target); --skip-stages leaves out the
// three small resolutions.
//   slimming_stages [--runs N] [--iterations N] [--end-to-end FACES] [--jitter MM] [--mesh PATH]
//                   [--skip-stages 1]
#include <algorithm>
#include <chrono>
#include <random>
#include <cstdio>
#include <string>
#include <vector>

#include "core/domain/voxel_domain.h"
#include "core/optimizer/slimming.h"
#include "core/solver/arap.h"
#include "support/shapes.h"

using namespace slim;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

long peak_rss_mb() {
  FILE* f = std::fopen("/proc/self/status", "r");
  char line[256];
  long kb = 0;
  while (f && std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmHWM: %ld kB", &kb) == 1) break;
  if (f) std::fclose(f);
  return kb / 1024;
}
// One whole run at the defaults on `start` refined to at least `faces`, every vertex moved by up to
// `jitter` mm (a fixed seed), stage by stage.
void run_end_to_end(const Surface& start, long faces, double jitter, int runs) {
  Surface big = start;
  while (big.F.rows() < faces) big = test::refined(big, 1);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Eigen::Index v = 0; v < big.V.rows() && jitter > 0.0; ++v) {
    Eigen::RowVector3d step;
    do step << unit(rng), unit(rng), unit(rng);
    while (step.squaredNorm() > 1.0);
    big.V.row(v) += jitter * step;
  }
  std::vector<double> total;
  SlimmingResult r;
  for (int k = 0; k < runs; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    r = slim_supports(big, {});
    total.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const auto& s = r.stage_seconds;
  if (jitter > 0.0) std::printf("(every vertex moved by up to %g mm)\n", jitter);
  std::printf("end to end, defaults, %ld faces: median %.2f s of %d runs; last run: %d iterations (returned %d); "
              "domain %.2f, embedding %.2f, factor %.2f, local %.2f, global %.2f, guards and statistics %.2f, "
              "support model %.2f, crease limit %.2f s\n", static_cast<long>(big.F.rows()), median(total), runs, r.iterations_run,
              r.iterations, s.domain, s.embedding, s.factorization, s.local, s.global, s.measure, s.support_model, s.creases);
  std::printf("peak memory (VmHWM): %ld MB\n", peak_rss_mb());
}
}  // namespace

int main(int argc, char** argv) {
  int runs = 5, iterations = 20;
  long end_to_end = 0;
  double jitter = 0.0;
  std::string mesh;
  bool stages = true;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--runs") runs = std::stoi(argv[i + 1]);
    if (a == "--iterations") iterations = std::stoi(argv[i + 1]);
    if (a == "--end-to-end") end_to_end = std::stol(argv[i + 1]);
    if (a == "--jitter") jitter = std::stod(argv[i + 1]);
    if (a == "--mesh") mesh = argv[i + 1];
    if (a == "--skip-stages") stages = std::string(argv[i + 1]) != "1";
  }
  const Surface bunny = test::load_mesh(test::sample_bunny_path());
  std::printf("median of %d runs of up to %d iterations, no budget, no stall stop; times in ms, per iteration\n"
              "(iteration = local + global + guards and statistics + the support model's estimate)\n"
              "actually run (the coherent inversion guard holds vertices back and goes on)\n", runs, iterations);
  std::printf("%10s %8s %8s %4s | %7s %7s %8s | %8s %8s %8s %9s | %7s %7s %6s | %8s\n", "resolution", "dom.V", "dom.T", "its",
              "domain", "embed", "factor", "local/it", "glob/it", "model/it", "iteration", "backsub", "ratio", "50 it", "total");
  for (int resolution : {13, 32, 60}) {
    if (!stages) break;
    std::vector<double> dom, emb, fac, loc, glo, model, it, back, total, ran_counts;
    SlimmingResult r;
    for (int k = 0; k < runs; ++k) {
      SlimmingOptions o;
      o.resolution = resolution;
      o.steps.max_iterations = iterations;
      o.budget = DeviationBudget::from_percent(0.0);
      o.steps.stall_tolerance = -1e300;  // run every iteration
      o.ladder.multiples.clear();  // this resolution alone: stage times add up over rungs
      const auto t0 = std::chrono::steady_clock::now();
      r = slim_supports(bunny, o);
      total.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      const auto& s = r.stage_seconds;
      dom.push_back(1e3 * s.domain);
      emb.push_back(1e3 * s.embedding);
      fac.push_back(1e3 * s.factorization);
      const int ran = std::max(1, r.iterations_run);
      loc.push_back(1e3 * s.local / ran);
      glo.push_back(1e3 * s.global / ran);
      model.push_back(1e3 * s.support_model / ran);
      it.push_back(1e3 * (s.local + s.global + s.measure + s.support_model) / ran);
      ran_counts.push_back(ran);
    }
    // One bare back-substitution of the same system (3 right-hand sides), in the same run.
    const VoxelDomain vd = voxel_domain(bunny, Eigen::Vector3d::UnitZ(), {resolution});
    std::vector<int> pinned;
    for (Eigen::Index v = 0; v < vd.on_plate.size(); ++v)
      if (vd.on_plate(v)) pinned.push_back(static_cast<int>(v));
    ArapOptions ao;
    ao.anchor_floating_components = true;
    const ArapSolver arap(vd.mesh, pinned, ao);
    const std::vector<Eigen::Matrix3d> L(static_cast<size_t>(vd.mesh.T.rows()), Eigen::Matrix3d::Identity());
    const Eigen::MatrixXd rhs = arap.assemble_rhs(L, vd.mesh.V);
    for (int k = 0; k < std::max(runs, 5); ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      const Eigen::MatrixXd x = arap.back_substitute(rhs);
      back.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      if (!x.allFinite()) return 1;
    }
    const double per_it = median(it);
    std::printf("%10d %8d %8d %4.0f | %7.1f %7.1f %8.1f | %8.2f %8.2f %8.2f %9.2f | %7.2f %7.1f %6.0f | %8.0f\n", resolution,
                r.domain_vertices, r.domain_tets, median(ran_counts), median(dom), median(emb), median(fac), median(loc), median(glo),
                median(model), per_it, median(back), per_it / median(back),
                median(dom) + median(emb) + median(fac) + 50 * per_it, median(total));
  }
  std::printf("peak memory (VmHWM): %ld MB\n", peak_rss_mb());
  if (end_to_end > 0) run_end_to_end(mesh.empty() ? bunny : test::load_mesh(mesh), end_to_end, jitter, runs);
  return 0;
}
