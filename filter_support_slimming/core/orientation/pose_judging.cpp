#include "core/orientation/pose_judging.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/orientation/pose_stability.h"
#include "core/platform/parallel_for.h"
#include "core/support_model/support_model.h"

namespace slim {
namespace orientation_search {

namespace {

// The poses a user would try, of each kind: hull planes, flat regions, normal clusters.
constexpr size_t kTriedOfEachKind = 8;
// Directions spread over the sphere that the model judges whatever their score: a pose whose
// shadow is large may still need little support, and no proxy-ranked list reaches it.
constexpr int kSphereForTheModel = 48;
// Sweep candidates the pool may draw on, best score first.
constexpr size_t kFromTheSweep = 256;
// The coarse pass's work: poses times faces, about a second on two cores.
constexpr double kCoarseFaceBudget = 1.2e6;
// Supports within this share (and kNoiseMm3) of the least are "about the same" for stability.
constexpr double kStabilityShare = 0.05;
// Supports within this share and kNoiseMm3 of the least are a tie the model cannot break.
constexpr double kNoiseShare = 0.01;
constexpr double kNoiseMm3 = 1.0;

// The pool the model judges, pose as given first, pairwise distinct_deg apart, at most `cap`.
class Pool {
 public:
  Pool(const OrientationGeometry& g, const OrientationOptions& o, size_t cap) : g_(g), o_(o), cap_(cap) {}
  void add(const OrientationCandidate& c) {
    if (poses.size() < cap_ && distinct(c.direction)) poses.push_back(c);
  }
  void add(const Eigen::Vector3d& d, const std::string& origin) {
    if (poses.size() < cap_ && distinct(d)) poses.push_back(exact_score(g_, d, origin));
  }
  bool full() const { return poses.size() >= cap_; }
  std::vector<OrientationCandidate> poses;

 private:
  bool distinct(const Eigen::Vector3d& d) const {
    return std::none_of(poses.begin(), poses.end(), [&](const OrientationCandidate& p) {
      return angle_between(p.direction, d) < o_.distinct_deg * M_PI / 180.0;
    });
  }
  const OrientationGeometry& g_;
  const OrientationOptions& o_;
  size_t cap_;
};

// The nearest pose resting on a hull facet or a flat region within distinct_deg of d, or d: an
// axis or a cluster a few degrees off a face the part can lie on means that face.
Eigen::Vector3d resting_near(const Candidates& c, const Eigen::Vector3d& d, const OrientationOptions& o) {
  Eigen::Vector3d nearest = d;
  double least = o.distinct_deg * M_PI / 180.0;
  for (const std::vector<size_t>* resting : {&c.hull_rest, &c.flat_down})
    for (size_t i : *resting) {
      const double angle = angle_between(c.dirs[i], d);
      if (angle < least) least = angle, nearest = c.dirs[i];
    }
  return nearest;
}

// The sources of the pool: the score's best, the hull planes and flat regions resting, the
// principal axes, the normal clusters face down (each moved onto a resting pose near it), the
// rest of the sweep by score.
std::vector<Candidates> pool_sources(const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                                 const std::vector<size_t>& ranked, const OrientationResult& result) {
  std::vector<Candidates> sources(7);  // the tie ranks are not read here
  for (const OrientationCandidate& t : result.top) sources[0].add(t.direction, t.origin, kOther);
  for (size_t k = 0; k < std::min(kTriedOfEachKind, c.hull_rest.size()); ++k) sources[1].add(c.dirs[c.hull_rest[k]], c.origins[c.hull_rest[k]], kOther);
  for (size_t k = 0; k < std::min(kTriedOfEachKind, c.flat_down.size()); ++k) sources[2].add(c.dirs[c.flat_down[k]], c.origins[c.flat_down[k]], kOther);
  for (const Eigen::Vector3d& axis : principal_axes(g)) {
    sources[3].add(resting_near(c, axis, o), "principal axis", kOther);
    sources[3].add(resting_near(c, -axis, o), "principal axis", kOther);
  }
  std::vector<size_t> bins(g.bins.size());
  std::iota(bins.begin(), bins.end(), size_t{0});
  std::stable_sort(bins.begin(), bins.end(), [&](size_t a, size_t b) { return g.bins[a].area > g.bins[b].area; });
  for (size_t k = 0; k < std::min(kTriedOfEachKind, bins.size()); ++k) sources[4].add(resting_near(c, -g.bins[bins[k]].axis, o), "face cluster down", kOther);
  for (size_t k = 0; k < std::min(ranked.size(), kFromTheSweep); ++k) sources[5].add(c.dirs[ranked[k]], c.origins[ranked[k]], kOther);
  for (const Eigen::Vector3d& d : fibonacci_sphere(kSphereForTheModel)) sources[6].add(d, "sphere", kOther);
  return sources;
}

// How many poses the model judges: support_model_candidates, fewer on a large mesh (the coarse
// pass costs about the same per face in every pose), never fewer than the finalists and the pose
// as given.
size_t pool_size(const OrientationGeometry& g, const OrientationOptions& o) {
  const double affordable = kCoarseFaceBudget / static_cast<double>(std::max<Eigen::Index>(1, g.faces));
  const size_t least = static_cast<size_t>(o.support_model_finalists) + 1;
  return std::max(least, std::min(static_cast<size_t>(o.support_model_candidates), static_cast<size_t>(affordable)));
}

// The pool: the pose as given, then one pose from each source in turn.
std::vector<OrientationCandidate> model_pool(const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                                             const std::vector<size_t>& ranked, const OrientationResult& result) {
  Pool pool(g, o, pool_size(g, o));
  pool.add(result.as_given);
  const std::vector<Candidates> sources = pool_sources(g, o, c, ranked, result);
  for (size_t k = 0; !pool.full(); ++k) {
    bool more = false;
    for (const Candidates& s : sources) {
      if (k >= s.dirs.size()) continue;
      more = true;
      pool.add(s.dirs[k], s.origins[k]);
    }
    if (!more) break;
  }
  return pool.poses;
}

// The model's estimate of one pose; none when it cannot judge it (no height).
std::optional<double> estimate(SupportModel& model, const Surface& surface, const OrientationOptions& o,
                               const Eigen::Vector3d& d, int grid_phases) {
  SupportModelOptions m;
  m.print.direction = d;
  m.print.alpha_max_deg = o.alpha_max_deg;
  m.grid_phases = grid_phases;
  if (grid_phases == 1) m.pixels_per_cell = 2;
  try {
    return model.estimate(surface.V, m).volume_mm3;
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// Every pose's estimate at one grid phase: the poses in one contiguous range per thread, each
// range with a model of its own (a model serves one call at a time; the figures do not depend on
// which model made them).
std::vector<std::optional<double>> coarse_estimates(const Surface& surface, const OrientationOptions& o,
                                                    const std::vector<OrientationCandidate>& pool) {
  std::vector<std::optional<double>> coarse(pool.size());
  const int ranges = std::max(1, std::min(omp_setting::threads(), static_cast<int>(pool.size())));
  parallel_for(ranges, [&](int r) {
    SupportModel model(surface.F, surface.V.rows());
    const size_t begin = pool.size() * static_cast<size_t>(r) / static_cast<size_t>(ranges);
    const size_t end = pool.size() * static_cast<size_t>(r + 1) / static_cast<size_t>(ranges);
    for (size_t k = begin; k < end; ++k) coarse[k] = estimate(model, surface, o, pool[k].direction, 1);
  });
  return coarse;
}

// The best `count` poses by the coarse estimate (none last), the pose as given (0) first.
std::vector<size_t> finalists(const std::vector<std::optional<double>>& coarse, size_t count) {
  std::vector<size_t> order(coarse.size() - 1);
  std::iota(order.begin(), order.end(), size_t{1});
  const double none = std::numeric_limits<double>::infinity();
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return coarse[a].value_or(none) < coarse[b].value_or(none); });
  order.resize(std::min(order.size(), count));
  order.insert(order.begin(), size_t{0});
  return order;
}

}  // namespace

std::optional<size_t> model_choice(const std::vector<OrientationCandidate>& judged) {
  auto least_of = [&](auto admit) {
    std::optional<double> least;
    for (const OrientationCandidate& c : judged)
      if (c.support_estimate && admit(c) && (!least || *c.support_estimate < *least)) least = c.support_estimate;
    return least;
  };
  const std::optional<double> least = least_of([](const OrientationCandidate&) { return true; });
  if (!least) return std::nullopt;
  auto within = [](const OrientationCandidate& c, double base, double share) {
    return c.support_estimate && *c.support_estimate <= base * (1.0 + share) + kNoiseMm3;
  };
  const bool any_stable = std::any_of(judged.begin(), judged.end(), [&](const OrientationCandidate& c) {
    return c.stable && within(c, *least, kStabilityShare);
  });
  auto admitted = [&](const OrientationCandidate& c) { return within(c, *least, kStabilityShare) && (c.stable || !any_stable); };
  const double base = *least_of(admitted);
  std::optional<size_t> best;
  for (size_t k = 0; k < judged.size(); ++k) {
    const OrientationCandidate& c = judged[k];
    if (!admitted(c) || !within(c, base, kNoiseShare)) continue;
    if (!best || c.contact_area > judged[*best].contact_area * (1.0 + 1e-9) + 1e-12) best = k;
  }
  return best;
}

std::vector<Eigen::Vector3d> principal_axes(const OrientationGeometry& g) {
  // Each triangle's own moments, exact: its integral of x is A s / 3 and of x x^T is
  // A / 12 (sum of v v^T + s s^T), s the sum of its corners.
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (Eigen::Index f = 0; f < g.faces; ++f) {
    const double area = g.area[static_cast<size_t>(f)];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d corners = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = g.V.row(g.F(f, k)).transpose();
      sum += v;
      corners += v * v.transpose();
    }
    first += area * sum / 3.0;
    second += area / 12.0 * (corners + sum * sum.transpose());
  }
  const Eigen::Vector3d mean = first / g.total_area;
  const Eigen::Matrix3d moment = second - g.total_area * mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(moment);
  std::vector<Eigen::Vector3d> axes;
  for (int k = 2; k >= 0; --k) axes.push_back(eigen.eigenvectors().col(k).normalized());
  return axes;
}

void judge_poses(const Surface& surface, const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                 const std::vector<size_t>& ranked, OrientationResult& result) {
  if (o.support_model_candidates == 0) return;
  std::vector<OrientationCandidate> pool = model_pool(g, o, c, ranked, result);
  // No coarse pass when every pose is a finalist.
  const bool prune = pool.size() > static_cast<size_t>(o.support_model_finalists) + 1;
  const std::vector<std::optional<double>> coarse = prune ? coarse_estimates(surface, o, pool)
                                                          : std::vector<std::optional<double>>(pool.size(), 0.0);
  SupportModel model(surface.F, surface.V.rows());  // one mesh in every pose
  result.judged_coarse = prune ? static_cast<int>(pool.size()) : 0;
  const Eigen::Vector3d centre = centre_of_mass(surface);
  std::vector<OrientationCandidate> judged;
  for (size_t k : finalists(coarse, static_cast<size_t>(o.support_model_finalists))) {
    OrientationCandidate candidate = pool[k];
    candidate.support_estimate = estimate(model, surface, o, candidate.direction, SupportModelOptions{}.grid_phases);
    const PoseRest rest = pose_rest(surface.V, candidate.direction, g.tolerance.value_or(0.0), centre);
    candidate.footprint_area = rest.footprint_mm2;
    candidate.stable = rest.stable;
    judged.push_back(candidate);
  }
  result.judged_fine = static_cast<int>(judged.size());
  result.as_given = judged.front();
  const std::optional<size_t> best = model_choice(judged);
  if (!best) return;  // nothing measurable: the score's choice stands
  const OrientationCandidate chosen = judged[*best];
  judged.erase(judged.begin() + static_cast<std::ptrdiff_t>(*best));
  if (*best != 0) judged.erase(judged.begin());  // the pose as given is listed only when chosen
  std::stable_sort(judged.begin(), judged.end(), [](const OrientationCandidate& a, const OrientationCandidate& b) {
    const double none = std::numeric_limits<double>::infinity();
    return a.support_estimate.value_or(none) < b.support_estimate.value_or(none);
  });
  judged.insert(judged.begin(), chosen);
  if (static_cast<int>(judged.size()) > o.report_count) judged.resize(static_cast<size_t>(o.report_count));
  result.top = judged;
  result.best = chosen;
  result.rotation = rotation_to_up(chosen.direction);
}

}  // namespace orientation_search
}  // namespace slim
