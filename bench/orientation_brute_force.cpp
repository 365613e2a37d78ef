// Print Orientation against brute force, by the support model: for each mesh and each of a few
// random starting poses (fixed seeds), the pose the search chooses against the least support the
// model finds over many directions on the sphere, and against the pose as modelled (upright).
//
//   build/bench/orientation_brute_force [--directions N] [--seeds K] MESH...
//   (eval: build/bench/orientation_brute_force data/corpus/*.ply)
//
// Per mesh and seed, one row: the model's estimate (mm³) of the chosen pose, of the best of N
// Fibonacci directions (default 300) and of the upright pose, the chosen one against the least
// of those two (%), whether the chosen pose stands by itself, the search's seconds, and the angle
// between the chosen direction and the brute force's best (degrees, in the mesh's frame). The
// brute force runs once per mesh, in the mesh's own frame: the turn moves only the slicer grid's
// phase, which the model averages. The last lines: how many rows are within 2% of the brute
// force (within 2% of the least of it and upright; a pose that stands may cost up to 5% more,
// by design), and the slowest search.
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "core/orientation/orientation.h"
#include "core/support_model/support_model.h"
#include "support/shapes.h"

using namespace slim;

namespace {

double estimate(SupportModel& model, const Surface& s, const Eigen::Vector3d& d) {
  SupportModelOptions m;
  m.print.direction = d;
  try {
    return model.estimate(s.V, m).volume_mm3;
  } catch (const std::exception&) {
    return INFINITY;
  }
}

struct Tally {
  int rows = 0, within_2 = 0, within_5 = 0;
  double slowest = 0.0;
};

void judge_mesh(const std::string& path, int directions, int seeds, Tally& tally) {
  const Surface mesh = test::load_mesh(path);
  SupportModel model(mesh.F, mesh.V.rows());
  double brute = INFINITY;
  Eigen::Vector3d brute_direction = Eigen::Vector3d::UnitZ();
  for (const Eigen::Vector3d& d : fibonacci_sphere(directions)) {
    const double e = estimate(model, mesh, d);
    if (e < brute) brute = e, brute_direction = d;
  }
  const std::string name = path.substr(path.find_last_of('/') + 1);
  std::mt19937_64 gen(2026);
  for (int seed = 0; seed < seeds; ++seed) {
    const Eigen::Matrix3d R = test::random_rotation(gen);
    const Surface turned = test::transformed(mesh, R);
    const OrientationResult r = optimize_orientation(turned);
    const double chosen = r.best.support_estimate.value_or(INFINITY);
    const double upright = estimate(model, turned, R * Eigen::Vector3d::UnitZ());
    const double least = std::min(brute, upright);
    const double pct = 100.0 * (chosen / std::max(least, 1e-9) - 1.0);
    ++tally.rows;
    tally.within_2 += chosen <= least * 1.02 + 1.0;
    tally.within_5 += chosen <= least * 1.05 + 1.0;
    tally.slowest = std::max(tally.slowest, r.seconds);
    const double apart = std::acos(std::clamp((R.transpose() * r.best.direction).dot(brute_direction), -1.0, 1.0)) * 180.0 / M_PI;
    std::printf("%-22s %4d %10.1f %10.1f %10.1f %+8.1f%% %-8s %6.2f %6.1f\n", name.c_str(), seed, chosen, brute, upright, pct,
                r.best.stable ? "stands" : "balances", r.seconds, apart);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int directions = 300, seeds = 3;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--directions" || a == "--seeds") && i + 1 < argc) {
      (a == "--directions" ? directions : seeds) = std::atoi(argv[++i]);
    } else {
      meshes.push_back(a);
    }
  }
  if (meshes.empty() || directions < 1 || seeds < 1) {
    std::fprintf(stderr, "usage: orientation_brute_force [--directions N] [--seeds K] MESH...\n");
    return 2;
  }
  std::printf("%-22s %4s %10s %10s %10s %9s %-8s %6s %6s\n", "mesh", "seed", "chosen", "brute", "upright", "vs least", "rest", "s",
              "deg");
  Tally tally;
  for (const std::string& path : meshes) judge_mesh(path, directions, seeds, tally);
  std::printf("within 2%% of the least of brute force and upright: %d of %d; within 5%%: %d of %d\n", tally.within_2,
              tally.rows, tally.within_5, tally.rows);
  std::printf("slowest search: %.2f s\n", tally.slowest);
  return 0;
}
