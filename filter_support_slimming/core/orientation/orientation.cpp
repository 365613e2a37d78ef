#include "core/orientation/orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/orientation/orientation_candidates.h"
#include "core/orientation/orientation_score.h"
#include "core/orientation/pose_judging.h"
#include "core/platform/parallel_for.h"
#include "core/print/overhang.h"

namespace slim {

namespace {

using namespace orientation_search;

// The pool, scored exactly, with the tie ranks: the pose as given, the best of the sweep, the
// refined ones (moved off any resting face).
struct Pool {
  std::vector<OrientationCandidate> scored;
  std::vector<TieRank> ranks;
};

Pool exact_pool(const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                const std::vector<size_t>& ranked, const std::vector<size_t>& starts,
                const std::vector<Eigen::Vector3d>& refined) {
  Candidates pool;
  pool.add(c.dirs[0], c.origins[0], c.ranks[0]);
  const size_t from_sweep = static_cast<size_t>(std::max(32, 2 * o.report_count));
  for (size_t k = 0; k < std::min(from_sweep, ranked.size()); ++k)
    if (ranked[k] != 0) pool.add(c.dirs[ranked[k]], c.origins[ranked[k]], c.ranks[ranked[k]]);
  for (size_t k = 0; k < starts.size(); ++k) pool.add(refined[k], c.origins[starts[k]] + " refined", kOther);
  Pool out{std::vector<OrientationCandidate>(pool.dirs.size()), pool.ranks};
  parallel_for(static_cast<int>(out.scored.size()), [&](int k) {
    out.scored[static_cast<size_t>(k)] = exact_score(g, pool.dirs[static_cast<size_t>(k)], pool.origins[static_cast<size_t>(k)]);
  });
  return out;
}

// The best of the pool: the least score; among scores equal up to rounding, the lowest tie rank,
// then the direction nearest +Z (the smallest turn), then the earliest in the pool. Then the best
// distinct others.
void choose_best(const OrientationGeometry& g, const OrientationOptions& o, const Pool& candidates, OrientationResult& result) {
  const std::vector<OrientationCandidate>& pool = candidates.scored;
  const double tie = 1e-9 * g.total_area * g.size;
  double least = pool[0].score;
  for (const OrientationCandidate& c : pool) least = std::min(least, c.score);
  size_t best = 0;
  bool found = false;
  auto preferred = [&](size_t k) {
    const TieRank rank = candidates.ranks[k], best_rank = candidates.ranks[best];
    return rank != best_rank ? rank < best_rank : pool[k].direction.z() > pool[best].direction.z();
  };
  for (size_t k = 0; k < pool.size(); ++k) {
    if (pool[k].score > least + tie) continue;
    if (!found || preferred(k)) best = k, found = true;
  }
  std::vector<size_t> order(pool.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return pool[a].score < pool[b].score; });
  result.top.push_back(pool[best]);
  for (size_t k : order) {
    if (static_cast<int>(result.top.size()) >= o.report_count) break;
    const bool distinct = std::none_of(result.top.begin(), result.top.end(), [&](const OrientationCandidate& t) {
      return angle_between(t.direction, pool[k].direction) < o.distinct_deg * M_PI / 180.0;
    });
    if (distinct) result.top.push_back(pool[k]);
  }
  result.best = pool[best];
  result.rotation = rotation_to_up(result.best.direction);
}

}  // namespace

std::vector<Eigen::Vector3d> fibonacci_sphere(int count) {
  if (count < 1) throw std::invalid_argument("the number of sphere directions must be at least 1");
  std::vector<Eigen::Vector3d> dirs(static_cast<size_t>(count));
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * i;
    dirs[static_cast<size_t>(i)] = Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z);
  }
  return dirs;
}

OrientationOptions with_effort(OrientationEffort effort, OrientationOptions base) {
  switch (effort) {
    case OrientationEffort::Fast:
      base.sphere_candidates = 1000, base.refine_starts = 4, base.support_model_candidates = 32, base.support_model_finalists = 4;
      break;
    case OrientationEffort::Normal:
      base.sphere_candidates = 4000, base.refine_starts = 8, base.support_model_candidates = 64, base.support_model_finalists = 8;
      break;
    case OrientationEffort::Thorough:
      base.sphere_candidates = 16000, base.refine_starts = 16, base.support_model_candidates = 128, base.support_model_finalists = 16;
      break;
  }
  return base;
}

OrientationCandidate score_orientation(const Surface& surface, const Eigen::Vector3d& direction,
                                       const OrientationOptions& options) {
  bool inside_out_input = false;
  const Eigen::Vector3d d = unit_print_direction(direction);
  if (surface.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to orient");
  const OrientationGeometry g = orientation_geometry(CheckedSurface(surface), options, false, inside_out_input);
  return exact_score(g, d, "given");
}

OrientationResult optimize_orientation(const Surface& surface, const OrientationOptions& o) {
  if (surface.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to orient");
  return optimize_orientation(CheckedSurface(surface), o);
}

OrientationResult optimize_orientation(const CheckedSurface& surface, const OrientationOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  ThreadScope threads(o.threads);
  OrientationResult result;
  const OrientationGeometry g = orientation_geometry(surface, o, true, result.inside_out);
  result.plate_tolerance_mm = g.tolerance;
  result.contact_bonus_height = g.bonus_height;
  result.hull_facets = static_cast<int>(g.hull.facets.size());

  const Candidates c = candidate_directions(g, o);
  const std::vector<double> swept = sweep_scores(g, c.dirs);
  result.candidates = static_cast<int>(c.dirs.size());
  std::vector<size_t> ranked(c.dirs.size());
  std::iota(ranked.begin(), ranked.end(), size_t{0});
  std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) { return swept[a] < swept[b]; });
  std::vector<Eigen::Vector3d> refined;
  const std::vector<size_t> starts = refine_best(g, o, c, ranked, refined, result.candidates);
  const Pool pool = exact_pool(g, o, c, ranked, starts, refined);
  result.as_given = pool.scored[0];
  choose_best(g, o, pool, result);
  const Surface& given = surface.get();
  judge_poses(result.inside_out ? flipped(given) : given, g, o, c, ranked, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

Eigen::Matrix<double, 3, 4> print_placement(const Surface& surface, const Eigen::Matrix3d& rotation) {
  if (surface.V.rows() == 0) throw std::invalid_argument("the mesh has no vertices: there is nothing to place");
  const Eigen::Vector3d c = surface.V.colwise().mean().transpose();
  Eigen::Matrix<double, 3, 4> placement;
  placement.leftCols<3>() = rotation;
  placement.col(3) = c - rotation * c;
  const double lowest = ((surface.V * rotation.row(2).transpose()).array() + placement(2, 3)).minCoeff();
  placement(2, 3) -= lowest;
  return placement;
}

Surface apply_orientation(const Surface& surface, const Eigen::Matrix3d& rotation) {
  const Eigen::Matrix<double, 3, 4> placement = print_placement(surface, rotation);
  Surface out = surface;
  out.V = (surface.V * placement.leftCols<3>().transpose()).rowwise() + placement.col(3).transpose();
  out.V.col(2).array() -= out.V.col(2).minCoeff();  // exactly on z = 0, whatever the rounding above
  return out;
}

OverhangReport print_pose_overhang(const Surface& posed, const OrientationResult& result, double alpha_max_deg) {
  PrintSetup print;
  print.alpha_max_deg = alpha_max_deg;
  print.plate = plate_rule_as_used(result);
  return analyse_overhang(result.inside_out ? flipped(posed) : posed, print);
}

}  // namespace slim
