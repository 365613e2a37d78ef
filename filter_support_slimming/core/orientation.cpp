#include "core/orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "core/orientation_score.h"
#include "core/overhang.h"
#include "core/parallel_for.h"
#include "core/support_model.h"

namespace slim {

namespace {

// Mesh faces whose normals lie within this angle of each other form one flat region (parallel
// faces). Generous enough for a float-rounded CAD face, far tighter than any curvature.
constexpr double kFlatRegionDeg = 1.0;
// Convex-hull facets within this angle lie in one plane: they differ only by rounding.
constexpr double kHullPlaneDeg = 0.05;
// A flat region smaller than this share of the surface is not worth a candidate.
constexpr double kMinFlatShare = 5e-3;
// The pattern search stops refining below this step.
constexpr double kMinStepDeg = 0.01;
constexpr int kMaxRefineSteps = 200;
// Directions the pattern search tries around its current one at each step.
constexpr int kAround = 8;

double radians(double degrees) { return degrees * M_PI / 180.0; }

struct Region {
  Eigen::Vector3d normal;
  double area;
};

// Unit area-weighted mean of the normals within `degrees` of m, with their area.
Region gather_region(const Eigen::Vector3d& m, const std::vector<double>& nx, const std::vector<double>& ny,
                     const std::vector<double>& nz, const std::vector<double>& area, double degrees) {
  const double min_cos = std::cos(radians(degrees));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (size_t i = 0; i < area.size(); ++i) {
    if (nx[i] * m.x() + ny[i] * m.y() + nz[i] * m.z() < min_cos) continue;
    sum += area[i] * Eigen::Vector3d(nx[i], ny[i], nz[i]);
    total += area[i];
  }
  return {sum.norm() > 0.0 ? Eigen::Vector3d(sum.normalized()) : m, total};
}

bool near_any(const std::vector<Region>& regions, const Eigen::Vector3d& n, double degrees) {
  const double min_cos = std::cos(radians(degrees));
  return std::any_of(regions.begin(), regions.end(), [&](const Region& r) { return r.normal.dot(n) >= min_cos; });
}

// The largest flat regions of the surface (parallel faces within kFlatRegionDeg), largest first.
// Seeds come from an area histogram of the normals on a cube map (31 cells a side: odd, so the
// axes, the commonest CAD normals, fall mid-cell); each region is then gathered exactly.
std::vector<Region> flat_regions(const OrientationGeometry& g, int max_count) {
  std::vector<Region> regions;
  if (max_count == 0) return regions;
  constexpr int R = 31;
  std::vector<double> bin_area(6 * R * R, 0.0);
  std::vector<Eigen::Vector3d> bin_normal(6 * R * R, Eigen::Vector3d::Zero());
  for (Eigen::Index f = 0; f < g.faces; ++f) {
    const auto i = static_cast<size_t>(f);
    const Eigen::Vector3d n(g.nx[i], g.ny[i], g.nz[i]);
    const int bin = cube_cell(n, R);
    bin_area[static_cast<size_t>(bin)] += g.area[i];
    bin_normal[static_cast<size_t>(bin)] += g.area[i] * n;
  }
  std::vector<int> order(bin_area.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return bin_area[static_cast<size_t>(a)] > bin_area[static_cast<size_t>(b)]; });
  const double min_seed = 0.2 * kMinFlatShare * g.total_area, min_region = kMinFlatShare * g.total_area;
  for (int bin : order) {
    if (static_cast<int>(regions.size()) >= max_count || bin_area[static_cast<size_t>(bin)] < min_seed) break;
    const Eigen::Vector3d seed = bin_normal[static_cast<size_t>(bin)];
    if (!(seed.norm() > 0.0) || near_any(regions, seed.normalized(), kFlatRegionDeg)) continue;
    const Region r = gather_region(seed.normalized(), g.nx, g.ny, g.nz, g.area, kFlatRegionDeg);
    if (r.area >= min_region && !near_any(regions, r.normal, kFlatRegionDeg)) regions.push_back(r);
  }
  std::stable_sort(regions.begin(), regions.end(), [](const Region& a, const Region& b) { return a.area > b.area; });
  return regions;
}

// The planes of the convex hull with the most area, largest first. A plane grows from its largest
// facet over the neighbouring facets whose normals lie within kHullPlaneDeg of that facet's (the
// seed's, not the neighbour's, so a finely faceted curve never creeps into one plane).
std::vector<Region> hull_planes(const OrientationGeometry& g, int max_count) {
  std::vector<Region> planes;
  const Eigen::Index h = static_cast<Eigen::Index>(g.hull.facets.size());
  if (max_count == 0 || h == 0) return planes;
  std::vector<Eigen::Index> order(static_cast<size_t>(h));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return g.hull.areas(a) > g.hull.areas(b); });
  const double min_cos = std::cos(radians(kHullPlaneDeg));
  std::vector<bool> taken(static_cast<size_t>(h), false);
  std::vector<int> patch;
  for (Eigen::Index seed : order) {
    if (taken[static_cast<size_t>(seed)]) continue;
    const Eigen::Vector3d n = g.hull.normals.row(seed).transpose();
    Region plane{Eigen::Vector3d::Zero(), 0.0};
    patch.assign(1, static_cast<int>(seed));
    taken[static_cast<size_t>(seed)] = true;
    for (size_t k = 0; k < patch.size(); ++k) {
      const int f = patch[k];
      plane.normal += g.hull.areas(f) * g.hull.normals.row(f).transpose();
      plane.area += g.hull.areas(f);
      for (int next : g.hull.neighbours[static_cast<size_t>(f)]) {
        if (next < 0 || taken[static_cast<size_t>(next)] || g.hull.normals.row(next).dot(n) < min_cos) continue;
        taken[static_cast<size_t>(next)] = true;
        patch.push_back(next);
      }
    }
    plane.normal = plane.normal.norm() > 0.0 ? Eigen::Vector3d(plane.normal.normalized()) : n;
    planes.push_back(plane);
  }
  std::stable_sort(planes.begin(), planes.end(), [](const Region& a, const Region& b) { return a.area > b.area; });
  if (static_cast<int>(planes.size()) > max_count) planes.resize(static_cast<size_t>(max_count));
  return planes;
}

// Two unit vectors perpendicular to d and to each other (a fixed choice: from X, or Y near X).
std::pair<Eigen::Vector3d, Eigen::Vector3d> tangent_basis(const Eigen::Vector3d& d) {
  const Eigen::Vector3d seed = std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = (seed - seed.dot(d) * d).normalized();
  return {t1, d.cross(t1)};
}

// Pattern search on the sphere from d: score kAround directions at `step` around it, move to the
// best if it beats the current one, else halve the step.
Eigen::Vector3d refine(const OrientationGeometry& g, Eigen::Vector3d d, double step, int& scored) {
  double current = sweep_scores(g, {d}).front();
  ++scored;
  const double min_step = radians(kMinStepDeg);
  for (int iteration = 0; iteration < kMaxRefineSteps && step >= min_step; ++iteration) {
    const auto [t1, t2] = tangent_basis(d);
    std::vector<Eigen::Vector3d> around(kAround);
    for (int k = 0; k < kAround; ++k) {
      const double angle = 2.0 * M_PI * k / kAround;
      around[static_cast<size_t>(k)] = (std::cos(step) * d + std::sin(step) * (std::cos(angle) * t1 + std::sin(angle) * t2)).normalized();
    }
    const std::vector<double> scores = sweep_scores(g, around);
    scored += kAround;
    const auto best = std::min_element(scores.begin(), scores.end());
    if (*best < current) {
      current = *best;
      d = around[static_cast<size_t>(best - scores.begin())];
    } else {
      step *= 0.5;
    }
  }
  return d;
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Among poses of equal score, which to prefer (the lower first): the pose as given (no turn at
// all), then one that rests a flat region or a hull facet exactly on the plate, then any other. A
// sphere or refined direction can tie with a resting face while tilted within the plate
// tolerance: its face would touch the plate along one edge only.
enum TieRank { kAsGiven = 0, kResting = 1, kOther = 2 };

// Every candidate direction with its origin (for people) and tie rank, the pose as given first.
struct Candidates {
  std::vector<Eigen::Vector3d> dirs;
  std::vector<std::string> origins;
  std::vector<TieRank> ranks;
  void add(const Eigen::Vector3d& d, const std::string& origin, TieRank rank) {
    dirs.push_back(d);
    origins.push_back(origin);
    ranks.push_back(rank);
  }
};

Candidates candidate_directions(const OrientationGeometry& g, const OrientationOptions& o) {
  Candidates c;
  c.add(Eigen::Vector3d::UnitZ(), "as given", kAsGiven);
  for (const Eigen::Vector3d& d : fibonacci_sphere(o.sphere_candidates)) c.add(d, "sphere", kOther);
  for (const Region& r : flat_regions(g, o.flat_regions)) {
    c.add(-r.normal, "flat face down", kResting);
    c.add(r.normal, "flat face up", kOther);
  }
  for (const Region& r : hull_planes(g, o.hull_facets)) c.add(-r.normal, "hull facet", kResting);
  return c;
}

// The best distinct swept candidates (indices into c), each refined from the sphere's spacing; the
// refined directions are appended to `refined` and their sweeps counted in `scored`.
std::vector<size_t> refine_best(const OrientationGeometry& g, const OrientationOptions& o, const Candidates& c,
                                const std::vector<size_t>& ranked, std::vector<Eigen::Vector3d>& refined, int& scored) {
  std::vector<size_t> starts;
  for (size_t i : ranked) {
    if (static_cast<int>(starts.size()) >= o.refine_starts) break;
    if (std::none_of(starts.begin(), starts.end(),
                     [&](size_t s) { return angle_between(c.dirs[s], c.dirs[i]) < radians(o.distinct_deg); }))
      starts.push_back(i);
  }
  const double spacing = std::sqrt(4.0 * M_PI / o.sphere_candidates);
  refined.assign(starts.size(), Eigen::Vector3d::Zero());
  std::vector<int> refine_scored(starts.size(), 0);
  // The starts run in parallel; the sweeps inside each are then serial (no nested regions).
  parallel_for(static_cast<int>(starts.size()), [&](int k) {
    refined[static_cast<size_t>(k)] = refine(g, c.dirs[starts[static_cast<size_t>(k)]], spacing, refine_scored[static_cast<size_t>(k)]);
  });
  for (int n : refine_scored) scored += n;
  return starts;
}

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
      return angle_between(t.direction, pool[k].direction) < radians(o.distinct_deg);
    });
    if (distinct) result.top.push_back(pool[k]);
  }
  result.best = pool[best];
  result.rotation = rotation_to_up(result.best.direction);
}

// The support model's verdict on the best candidates (step 5): each judged in its pose, the least
// support first; the score decides between supports within 1% (+1 mm³: the model's phase noise).
void judge_by_support(const Surface& oriented, const OrientationOptions& o, OrientationResult& result) {
  const size_t judged = std::min(result.top.size(), static_cast<size_t>(std::max(0, o.support_model_candidates)));
  if (judged == 0) return;
  SupportModel model(oriented.F, oriented.V.rows());  // one mesh in every pose
  auto estimate = [&](OrientationCandidate& c) {
    SupportModelOptions m;
    m.print_direction = c.direction;
    m.alpha_max_deg = o.alpha_max_deg;
    try {
      c.support_estimate = model.estimate(oriented.V, m).volume_mm3;
    } catch (const std::invalid_argument&) {
      c.support_estimate = -1.0;  // the model cannot judge this pose (no height): the score stands
    }
  };
  estimate(result.as_given);
  for (size_t k = 0; k < judged; ++k) estimate(result.top[k]);
  size_t best = 0;
  for (size_t k = 1; k < judged; ++k) {
    const double s = result.top[k].support_estimate, b = result.top[best].support_estimate;
    if (s < 0.0) continue;
    if (b < 0.0 || s < b - (0.01 * b + 1.0)) best = k;
  }
  std::rotate(result.top.begin(), result.top.begin() + static_cast<std::ptrdiff_t>(best),
              result.top.begin() + static_cast<std::ptrdiff_t>(best) + 1);
  // The pose as given is a candidate too: no turn at all when it needs clearly less support than
  // every pose the score ranked first (a duck of the corpus: 1.3% more support turned).
  const double given = result.as_given.support_estimate, turned = result.top.front().support_estimate;
  if (given >= 0.0 && (turned < 0.0 || given < turned - (0.01 * turned + 1.0)))
    result.top.insert(result.top.begin(), result.as_given);
  result.best = result.top.front();
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
    case OrientationEffort::Fast: base.sphere_candidates = 1000, base.refine_starts = 4; break;
    case OrientationEffort::Normal: base.sphere_candidates = 4000, base.refine_starts = 8; break;
    case OrientationEffort::Thorough: base.sphere_candidates = 16000, base.refine_starts = 16; break;
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
  result.plate_tolerance = g.tolerance;
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
  judge_by_support(result.inside_out ? flipped(given) : given, o, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

Eigen::Matrix3d rotation_to_up(const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = unit_print_direction(d);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d axis = u.cross(up);
  const double sin_angle = axis.norm(), cos_angle = u.dot(up);
  if (sin_angle < 1e-15) {
    return cos_angle > 0.0 ? Eigen::Matrix3d::Identity() : Eigen::Matrix3d(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  }
  return Eigen::AngleAxisd(std::atan2(sin_angle, cos_angle), axis / sin_angle).toRotationMatrix();
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
  OverhangOptions o;
  o.alpha_max_deg = alpha_max_deg;
  o.plate_tolerance = result.plate_tolerance;
  return analyse_overhang(result.inside_out ? flipped(posed) : posed, o);
}

}  // namespace slim
