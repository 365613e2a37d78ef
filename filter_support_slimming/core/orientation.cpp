#include "core/orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "core/convex_hull.h"
#include "core/overhang.h"
#include "core/parallel_for.h"

namespace slim {

namespace {

// The sweep scores directions in blocks of this many (one plate product per block, and the unit
// of parallel work).
constexpr int kBlock = 64;
// Sweep bins: about this many faces per cube-map cell of normals (see NormalBin).
constexpr double kFacesPerBin = 32.0;
// A bin within this angle (plus its own radius) of -d may hold faces lying on the plate: the sweep
// then visits its faces one by one, so that their area counts as contact.
constexpr double kNearPlateDeg = 2.0;
// Angular slack of the bin bounds, far above the rounding of the dot products.
constexpr double kBinSlack = 1e-9;
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
// Directions whose lowest hull vertex is known, to start the plate walks near their end.
constexpr int kAnchors = 64;
// Hull tolerance: 1e-9 of the part size, far above the rounding of the coordinates.
constexpr double kHullEps = 1e-9;

double radians(double degrees) { return degrees * M_PI / 180.0; }

// Faces whose normals fall in one cube-map cell, with what the sweep needs to add them up at once.
// For a direction d, let theta be the angle between d and the bin's axis and beta = acos(-tau) the
// angle from d beyond which a normal is risky. Every face of the bin lies within `radius` of the
// axis, so theta > beta + radius makes them all risky and theta < beta - radius all safe; only
// the bins in between (a band around the circle of the threshold) are visited face by face. An
// all-risky bin adds
//   sum of area * -(n·d) * (c·d - plate) = -d^T (sum of area * n c^T) d + plate * (sum of area * n)·d.
struct NormalBin {
  Eigen::Index begin = 0, end = 0;  // its faces, in Geometry's face order
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit area-weighted mean normal
  Eigen::Matrix3d normal_centroid = Eigen::Matrix3d::Zero();  // sum of area * n c^T
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();       // sum of area * n
  double area = 0.0;
  double cos_all_risky = -2.0;  // axis·d below this: every face risky (-2: never)
  double cos_all_safe = 2.0;    // axis·d above this: every face safe (2: never)
  double cos_near_plate = 2.0;  // -axis·d above this: visit face by face
};

// Everything per face that a score needs, computed once, as structure-of-arrays: the faces with a
// positive area (the others add nothing to any score), ordered by normal bin, positions relative
// to the vertices' centroid so that heights lose no digits for a part far from the origin.
struct Geometry {
  Points V;  // #V by 3, relative to `centre`
  Triangles F;  // the kept faces, in bin order
  Eigen::Vector3d centre;
  Eigen::Index faces = 0;
  std::vector<double> nx, ny, nz, cx, cy, cz, area;
  std::vector<NormalBin> bins;
  Points extreme;  // the convex hull's vertices (relative), or every vertex when there is no hull
  ConvexHull hull;
  // The hull's vertex graph (CSR over the rows of `extreme`), and anchor directions with their
  // lowest hull vertex, where the walks of sweep_plate() start.
  std::vector<int> adjacency_start, adjacency;
  Eigen::Matrix3Xd anchors;
  std::vector<int> anchor_lowest;
  double size = 0.0, total_area = 0.0, tau = 0.0, tolerance = 0.0, bonus_height = 0.0;
};

// The cell of a unit vector on a cube map with R by R cells on each of the cube's six faces.
int cube_cell(const Eigen::Vector3d& n, int R) {
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  const double scale = 1.0 / std::abs(n(axis));
  auto cell = [&](double t) { return std::clamp(static_cast<int>((t * scale + 1.0) * 0.5 * R), 0, R - 1); };
  return ((2 * axis + (n(axis) < 0 ? 1 : 0)) * R + cell(n((axis + 1) % 3))) * R + cell(n((axis + 2) % 3));
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

namespace {

void check_options(const OrientationOptions& o) {
  self_supporting_tau(o.alpha_max_deg);
  if (!std::isfinite(o.plate_tolerance)) throw std::invalid_argument("the build plate tolerance must be finite");
  if (!(o.contact_bonus >= 0.0 && std::isfinite(o.contact_bonus)))
    throw std::invalid_argument("the plate contact bonus must be a finite share >= 0");
  if (o.sphere_candidates < 1 || o.sphere_candidates > 10000000)
    throw std::invalid_argument("the number of sphere directions must be in [1, 10000000], got " +
                                std::to_string(o.sphere_candidates));
  if (o.flat_regions < 0) throw std::invalid_argument("the number of flat regions tried must be 0 or more");
  if (o.hull_facets < 0) throw std::invalid_argument("the number of convex-hull facets tried must be 0 or more");
  if (o.refine_starts < 0) throw std::invalid_argument("the number of refined candidates must be 0 or more");
  if (o.report_count < 1) throw std::invalid_argument("at least one candidate must be reported");
  if (!(o.distinct_deg >= 0.0 && o.distinct_deg <= 180.0))
    throw std::invalid_argument("the angle between distinct candidates must be in [0, 180] degrees");
  if (o.threads < 0) throw std::invalid_argument("the thread count must be 0 (the default) or more");
}

// Validates the input and precomputes the per-face table, the hull and the constants.
Geometry prepare(const Surface& s, const OrientationOptions& o, bool with_hull, bool& inside_out_input) {
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to orient");
  check_surface(s);
  check_options(o);
  const EdgeTopology edges = edge_topology(s);
  require_consistent_orientation(edges);  // no outside, so no overhang to judge
  inside_out_input = inside_out(s, edges);

  Geometry g;
  g.centre = s.V.colwise().mean().transpose();
  g.V = s.V.rowwise() - g.centre.transpose();
  g.F = s.F;
  g.size = 2.0 * g.V.rowwise().norm().maxCoeff();
  if (!(g.size > 0.0)) throw std::invalid_argument("the mesh has zero extent (all its vertices coincide): there is nothing to orient");
  Points n = face_normals(s);
  if (inside_out_input) n = -n;  // every normal pointed into the part
  const Eigen::VectorXd a = face_areas(s);
  g.total_area = a.sum();
  if (!(g.total_area > 0.0)) throw std::invalid_argument("every face has zero area: there is no surface to orient");
  g.tau = self_supporting_tau(o.alpha_max_deg);
  g.tolerance = o.plate_tolerance >= 0.0 ? o.plate_tolerance : 1e-3 * g.size;
  g.bonus_height = o.contact_bonus * g.size;

  // The kept faces, bin by bin (stable: the input's order within a bin).
  const int R = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(s.F.rows()) / (6.0 * kFacesPerBin))), 1, 96);
  std::vector<std::pair<int, Eigen::Index>> order;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (a(f) > 0.0) order.emplace_back(cube_cell(n.row(f).transpose(), R), f);
  std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  g.faces = static_cast<Eigen::Index>(order.size());
  g.F.resize(g.faces, 3);
  for (auto* column : {&g.nx, &g.ny, &g.nz, &g.cx, &g.cy, &g.cz, &g.area}) column->assign(order.size(), 0.0);
  const double beta = std::acos(-g.tau);
  for (size_t k = 0; k < order.size(); ++k) {
    const Eigen::Index f = order[k].second;
    const Eigen::Vector3d c = (g.V.row(s.F(f, 0)) + g.V.row(s.F(f, 1)) + g.V.row(s.F(f, 2))).transpose() / 3.0;
    g.F.row(static_cast<Eigen::Index>(k)) = s.F.row(f);
    g.nx[k] = n(f, 0), g.ny[k] = n(f, 1), g.nz[k] = n(f, 2);
    g.cx[k] = c(0), g.cy[k] = c(1), g.cz[k] = c(2);
    g.area[k] = a(f);
    if (k == 0 || order[k].first != order[k - 1].first) {
      g.bins.emplace_back();
      g.bins.back().begin = static_cast<Eigen::Index>(k);
    }
    NormalBin& bin = g.bins.back();
    bin.end = static_cast<Eigen::Index>(k) + 1;
    bin.normal_centroid += a(f) * n.row(f).transpose() * c.transpose();
    bin.normal_sum += a(f) * n.row(f).transpose();
    bin.area += a(f);
  }
  for (NormalBin& bin : g.bins) {
    if (bin.normal_sum.norm() > 0.0) bin.axis = bin.normal_sum.normalized();
    double radius = 0.0;
    for (Eigen::Index k = bin.begin; k < bin.end; ++k) {
      const auto i = static_cast<size_t>(k);
      const double along = std::clamp(bin.axis.dot(Eigen::Vector3d(g.nx[i], g.ny[i], g.nz[i])), -1.0, 1.0);
      radius = std::max(radius, std::acos(along));
    }
    radius += kBinSlack;
    if (beta + radius < M_PI) bin.cos_all_risky = std::cos(beta + radius);
    if (beta - radius > 0.0) bin.cos_all_safe = std::cos(beta - radius);
    if (radius + radians(kNearPlateDeg) < M_PI) bin.cos_near_plate = std::cos(radius + radians(kNearPlateDeg));
  }

  if (with_hull && convex_hull(g.V, kHullEps * g.size, g.hull)) {
    g.extreme.resize(static_cast<Eigen::Index>(g.hull.vertices.size()), 3);
    std::vector<int> row_of(static_cast<size_t>(g.V.rows()), -1);
    for (size_t k = 0; k < g.hull.vertices.size(); ++k) {
      g.extreme.row(static_cast<Eigen::Index>(k)) = g.V.row(g.hull.vertices[k]);
      row_of[static_cast<size_t>(g.hull.vertices[k])] = static_cast<int>(k);
    }
    // Each facet edge once per direction: a -> b and b -> a both appear, once in each facet.
    g.adjacency_start.assign(g.hull.vertices.size() + 1, 0);
    for (const auto& f : g.hull.facets)
      for (int e = 0; e < 3; ++e) ++g.adjacency_start[static_cast<size_t>(row_of[static_cast<size_t>(f[static_cast<size_t>(e)])]) + 1];
    for (size_t k = 1; k < g.adjacency_start.size(); ++k) g.adjacency_start[k] += g.adjacency_start[k - 1];
    g.adjacency.resize(static_cast<size_t>(g.adjacency_start.back()));
    std::vector<int> fill(g.adjacency_start.begin(), g.adjacency_start.end() - 1);
    for (const auto& f : g.hull.facets)
      for (int e = 0; e < 3; ++e)
        g.adjacency[static_cast<size_t>(fill[static_cast<size_t>(row_of[static_cast<size_t>(f[static_cast<size_t>(e)])])]++)] =
            row_of[static_cast<size_t>(f[static_cast<size_t>((e + 1) % 3)])];
    const std::vector<Eigen::Vector3d> anchors = fibonacci_sphere(kAnchors);
    g.anchors.resize(3, kAnchors);
    for (int k = 0; k < kAnchors; ++k) {
      g.anchors.col(k) = anchors[static_cast<size_t>(k)];
      Eigen::Index lowest = 0;
      (g.extreme * anchors[static_cast<size_t>(k)]).minCoeff(&lowest);
      g.anchor_lowest.push_back(static_cast<int>(lowest));
    }
  } else {
    g.extreme = g.V;
  }
  return g;
}

struct FaceSums {
  double shadow = 0.0;      // sum over risky faces of area * -(n·d) * height above the plate
  double risky_area = 0.0;
  double near_area = 0.0;   // faces whose centroid lies within the plate tolerance
};

// The sweep's sums for one direction and its plate height. Every risky face counts, plate faces
// included: their shadow is below area * tolerance each, and the area of the faces whose centroid
// touches the plate (counted in the bins visited face by face, which include every bin facing
// the plate) stands in for the contact area. score_exactly() applies the plate rule face by face.
FaceSums sweep_sums(const Geometry& g, const Eigen::Vector3d& d, double plate) {
  FaceSums sums;
  const double minus_tau = -g.tau;
  for (const NormalBin& bin : g.bins) {
    const double along = bin.axis.dot(d);
    if (along > bin.cos_all_safe) continue;
    if (along < bin.cos_all_risky && -along <= bin.cos_near_plate) {
      sums.shadow += plate * bin.normal_sum.dot(d) - d.dot(bin.normal_centroid * d);
      sums.risky_area += bin.area;
      continue;
    }
    for (Eigen::Index k = bin.begin; k < bin.end; ++k) {
      const auto i = static_cast<size_t>(k);
      const double nd = g.nx[i] * d.x() + g.ny[i] * d.y() + g.nz[i] * d.z();
      const double h = g.cx[i] * d.x() + g.cy[i] * d.y() + g.cz[i] * d.z() - plate;
      if (nd < minus_tau) {
        sums.shadow += -(g.area[i] * nd) * h;
        sums.risky_area += g.area[i];
      }
      if (h <= g.tolerance) sums.near_area += g.area[i];
    }
  }
  return sums;
}

// The plate height min over vertices of v·d from the hull: from the lowest vertex of the nearest
// anchor direction, step to the lowest neighbour while that is lower. On a convex polytope the
// first vertex with no lower neighbour is the lowest of all; the hull is convex to within its eps,
// so the height is too.
double sweep_plate(const Geometry& g, const Eigen::Vector3d& d) {
  Eigen::Index nearest = 0;
  (d.transpose() * g.anchors).maxCoeff(&nearest);
  int v = g.anchor_lowest[static_cast<size_t>(nearest)];
  double height = g.extreme.row(v).dot(d);
  for (bool lower = true; lower;) {
    lower = false;
    int next = v;
    for (int k = g.adjacency_start[static_cast<size_t>(v)]; k < g.adjacency_start[static_cast<size_t>(v) + 1]; ++k) {
      const int u = g.adjacency[static_cast<size_t>(k)];
      const double h = g.extreme.row(u).dot(d);
      if (h < height) height = h, next = u, lower = true;
    }
    v = next;
  }
  return height;
}

// Sweep scores for any number of directions: blocks of kBlock in parallel, each block's plate
// heights from the hull's vertices in one product.
std::vector<double> sweep_scores(const Geometry& g, const std::vector<Eigen::Vector3d>& dirs) {
  std::vector<double> scores(dirs.size());
  const int blocks = static_cast<int>((dirs.size() + kBlock - 1) / kBlock);
  parallel_for(blocks, [&](int b) {
    const size_t first = static_cast<size_t>(b) * kBlock;
    const Eigen::Index count = static_cast<Eigen::Index>(std::min<size_t>(kBlock, dirs.size() - first));
    Eigen::Matrix3Xd D(3, count);
    for (Eigen::Index k = 0; k < count; ++k) D.col(k) = dirs[first + static_cast<size_t>(k)];
    // Without a hull, one product for the block.
    if (g.adjacency.empty()) {
      const Eigen::RowVectorXd plate = (g.extreme * D).colwise().minCoeff();
      for (Eigen::Index k = 0; k < count; ++k) {
        const FaceSums sums = sweep_sums(g, D.col(k), plate(k));
        scores[first + static_cast<size_t>(k)] = sums.shadow - g.bonus_height * sums.near_area;
      }
      return;
    }
    for (Eigen::Index k = 0; k < count; ++k) {
      const FaceSums sums = sweep_sums(g, D.col(k), sweep_plate(g, D.col(k)));
      scores[first + static_cast<size_t>(k)] = sums.shadow - g.bonus_height * sums.near_area;
    }
  });
  return scores;
}

// The score exactly as orientation.h defines it: the plate from every vertex, the plate rule face
// by face (as analyse_overhang applies it).
OrientationCandidate score_exactly(const Geometry& g, const Eigen::Vector3d& d, const std::string& origin) {
  const Eigen::VectorXd height = g.V * d;
  const double plate = height.minCoeff();
  OrientationCandidate c;
  c.direction = d;
  c.origin = origin;
  for (Eigen::Index f = 0; f < g.faces; ++f) {
    const auto i = static_cast<size_t>(f);
    if (height(g.F(f, 0)) - plate <= g.tolerance && height(g.F(f, 1)) - plate <= g.tolerance &&
        height(g.F(f, 2)) - plate <= g.tolerance) {
      c.contact_area += g.area[i];
      continue;
    }
    const double nd = g.nx[i] * d.x() + g.ny[i] * d.y() + g.nz[i] * d.z();
    if (nd < -g.tau) {
      const double above_plate = g.cx[i] * d.x() + g.cy[i] * d.y() + g.cz[i] * d.z() - plate;
      c.shadow_volume += g.area[i] * -nd * above_plate;
      c.risky_area += g.area[i];
    }
  }
  c.score = c.shadow_volume - g.bonus_height * c.contact_area;
  return c;
}

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
std::vector<Region> flat_regions(const Geometry& g, int max_count) {
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
std::vector<Region> hull_planes(const Geometry& g, int max_count) {
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
Eigen::Vector3d refine(const Geometry& g, Eigen::Vector3d d, double step, int& scored) {
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

}  // namespace

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
  const Geometry g = prepare(surface, options, false, inside_out_input);
  return score_exactly(g, d, "given");
}

OrientationResult optimize_orientation(const Surface& surface, const OrientationOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  ThreadScope threads(o.threads);
  OrientationResult result;
  const Geometry g = prepare(surface, o, true, result.inside_out);
  result.plate_tolerance = g.tolerance;
  result.contact_bonus_height = g.bonus_height;
  result.hull_facets = static_cast<int>(g.hull.facets.size());

  // 1. Candidates, the pose as given first (so that it wins every tie it is part of).
  std::vector<Eigen::Vector3d> dirs{Eigen::Vector3d::UnitZ()};
  std::vector<std::string> origins{"as given"};
  for (const Eigen::Vector3d& d : fibonacci_sphere(o.sphere_candidates)) dirs.push_back(d), origins.push_back("sphere");
  for (const Region& r : flat_regions(g, o.flat_regions)) {
    dirs.push_back(-r.normal), origins.push_back("flat face down");
    dirs.push_back(r.normal), origins.push_back("flat face up");
  }
  for (const Region& r : hull_planes(g, o.hull_facets)) dirs.push_back(-r.normal), origins.push_back("hull facet");

  // 2. The sweep.
  const std::vector<double> swept = sweep_scores(g, dirs);
  result.candidates = static_cast<int>(dirs.size());
  std::vector<size_t> ranked(dirs.size());
  std::iota(ranked.begin(), ranked.end(), size_t{0});
  std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) { return swept[a] < swept[b]; });

  // 3. Refinement of the best distinct candidates, started at the sphere's spacing.
  std::vector<size_t> starts;
  for (size_t i : ranked) {
    if (static_cast<int>(starts.size()) >= o.refine_starts) break;
    if (std::none_of(starts.begin(), starts.end(),
                     [&](size_t s) { return angle_between(dirs[s], dirs[i]) < radians(o.distinct_deg); }))
      starts.push_back(i);
  }
  const double spacing = std::sqrt(4.0 * M_PI / o.sphere_candidates);
  std::vector<Eigen::Vector3d> refined(starts.size());
  std::vector<int> refine_scored(starts.size(), 0);
  // The starts run in parallel; the sweeps inside each are then serial (no nested regions).
  parallel_for(static_cast<int>(starts.size()), [&](int k) {
    refined[static_cast<size_t>(k)] = refine(g, dirs[starts[static_cast<size_t>(k)]], spacing, refine_scored[static_cast<size_t>(k)]);
  });
  for (int n : refine_scored) result.candidates += n;

  // 4. The pool, scored exactly: the pose as given, the best of the sweep, the refined ones.
  std::vector<Eigen::Vector3d> pool_dirs{dirs[0]};
  std::vector<std::string> pool_origins{origins[0]};
  const size_t from_sweep = static_cast<size_t>(std::max(32, 2 * o.report_count));
  for (size_t k = 0; k < std::min(from_sweep, ranked.size()); ++k) {
    if (ranked[k] == 0) continue;
    pool_dirs.push_back(dirs[ranked[k]]);
    pool_origins.push_back(origins[ranked[k]]);
  }
  for (size_t k = 0; k < starts.size(); ++k) {
    pool_dirs.push_back(refined[k]);
    pool_origins.push_back(origins[starts[k]] + " refined");
  }
  std::vector<OrientationCandidate> pool(pool_dirs.size());
  parallel_for(static_cast<int>(pool.size()), [&](int k) {
    pool[static_cast<size_t>(k)] = score_exactly(g, pool_dirs[static_cast<size_t>(k)], pool_origins[static_cast<size_t>(k)]);
  });
  result.as_given = pool[0];

  // The best: the least score; among scores equal up to rounding, the direction nearest +Z (the
  // smallest turn), then the earliest in the pool.
  const double tie = 1e-9 * g.total_area * g.size;
  double least = pool[0].score;
  for (const OrientationCandidate& c : pool) least = std::min(least, c.score);
  size_t best = 0;
  bool found = false;
  for (size_t k = 0; k < pool.size(); ++k) {
    if (pool[k].score > least + tie) continue;
    if (!found || pool[k].direction.z() > pool[best].direction.z()) best = k, found = true;
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
