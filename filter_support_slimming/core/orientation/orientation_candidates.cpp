#include "core/orientation/orientation_candidates.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "core/platform/parallel_for.h"

namespace slim {
namespace orientation_search {

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

}  // namespace

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Candidates candidate_directions(const OrientationGeometry& g, const OrientationOptions& o) {
  Candidates c;
  c.add(Eigen::Vector3d::UnitZ(), "as given", kAsGiven);
  for (const Eigen::Vector3d& d : fibonacci_sphere(o.sphere_candidates)) c.add(d, "sphere", kOther);
  for (const Region& r : flat_regions(g, o.flat_regions)) {
    c.flat_down.push_back(c.dirs.size());
    c.add(-r.normal, "flat face down", kResting);
    c.add(r.normal, "flat face up", kOther);
  }
  for (const Region& r : hull_planes(g, o.hull_facets)) {
    c.hull_rest.push_back(c.dirs.size());
    c.add(-r.normal, "hull facet", kResting);
  }
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

}  // namespace orientation_search
}  // namespace slim
