#include "core/orientation/orientation_score.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/platform/parallel_for.h"
#include "core/print/overhang.h"

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
// Directions whose lowest hull vertex is known, to start the plate walks near their end.
constexpr int kAnchors = 64;
// Hull tolerance: 1e-9 of the part size, far above the rounding of the coordinates.
constexpr double kHullEps = 1e-9;

double radians(double degrees) { return degrees * M_PI / 180.0; }


void check_options(const OrientationOptions& o) {
  self_supporting_tau(o.alpha_max_deg);
  o.plate.tolerance_mm(1.0);  // refuses a bad tolerance before any work
  if (!(o.contact_bonus >= 0.0 && std::isfinite(o.contact_bonus)))
    throw std::invalid_argument("the plate contact bonus must be a finite share >= 0");
  if (o.sphere_candidates < 1 || o.sphere_candidates > 10000000)
    throw std::invalid_argument("the number of sphere directions must be in [1, 10000000], got " +
                                std::to_string(o.sphere_candidates));
  if (o.flat_regions < 0) throw std::invalid_argument("the number of flat regions tried must be 0 or more");
  if (o.hull_facets < 0) throw std::invalid_argument("the number of convex-hull facets tried must be 0 or more");
  if (o.refine_starts < 0) throw std::invalid_argument("the number of refined candidates must be 0 or more");
  if (o.support_model_candidates < 0 || o.support_model_finalists < 0)
    throw std::invalid_argument("the number of poses the support model judges must be 0 or more");
  if (o.report_count < 1) throw std::invalid_argument("at least one candidate must be reported");
  if (!(o.distinct_deg >= 0.0 && o.distinct_deg <= 180.0))
    throw std::invalid_argument("the angle between distinct candidates must be in [0, 180] degrees");
  if (o.threads < 0) throw std::invalid_argument("the thread count must be 0 (the default) or more");
}


// The kept faces (positive area), bin by bin (stable: the input's order within a bin), with each
// bin's sums and the cones that bound its normals. n: the outward unit normals, a: the areas.
void bin_faces(const Surface& s, const Points& n, const Eigen::VectorXd& a, OrientationGeometry& g) {
  const int R = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(s.F.rows()) / (6.0 * kFacesPerBin))), 1, 96);
  std::vector<std::pair<int, Eigen::Index>> order;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (a(f) > 0.0) order.emplace_back(cube_cell(n.row(f).transpose(), R), f);
  std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  g.faces = static_cast<Eigen::Index>(order.size());
  g.F.resize(g.faces, 3);
  for (auto* column : {&g.nx, &g.ny, &g.nz, &g.cx, &g.cy, &g.cz, &g.area}) column->assign(order.size(), 0.0);
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
  const double beta = std::acos(-g.tau);
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
}

// The convex hull, its vertices as the extreme points and their graph, and the anchors of the
// plate walks; without a hull, every vertex is an extreme point.
void build_hull(OrientationGeometry& g) {
  if (!convex_hull(g.V, kHullEps * g.size, g.hull)) {
    g.extreme = g.V;
    return;
  }
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
}

struct FaceSums {
  double shadow = 0.0;      // sum over risky faces of area * -(n·d) * height above the plate
  double risky_area = 0.0;
  double near_area = 0.0;   // faces whose centroid lies within the plate tolerance
};

// The sweep's sums for one direction and its plate height. Every risky face counts, plate faces
// included: their shadow is below area * tolerance each, and the area of the faces whose centroid
// touches the plate (counted in the bins visited face by face, which include every bin facing
// the plate) stands in for the contact area. exact_score() applies the plate rule face by face.
FaceSums sweep_sums(const OrientationGeometry& g, const Eigen::Vector3d& d, double plate) {
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
      if (g.tolerance && h <= *g.tolerance) sums.near_area += g.area[i];
    }
  }
  return sums;
}

// The plate height min over vertices of v·d from the hull: from the lowest vertex of the nearest
// anchor direction, step to the lowest neighbour while that is lower. On a convex polytope the
// first vertex with no lower neighbour is the lowest of all; the hull is convex to within its eps,
// so the height is too.
double sweep_plate(const OrientationGeometry& g, const Eigen::Vector3d& d) {
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

}  // namespace

OrientationGeometry orientation_geometry(const CheckedSurface& checked, const OrientationOptions& o, bool with_hull,
                                         bool& inside_out_input) {
  const Surface& s = checked.get();
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: there is nothing to orient");
  check_options(o);
  const EdgeTopology edges = edge_topology(s);
  require_consistent_orientation(edges);  // no outside, so no overhang to judge
  inside_out_input = inside_out(s, edges);

  OrientationGeometry g;
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
  // Of the part as given, one length for every pose, so that the slimming in the chosen pose sees
  // the plate as the search did, and a part left as given is slimmed as it is without the search.
  g.tolerance = o.plate.tolerance_mm(bbox_diagonal(s.V));
  g.bonus_height = o.contact_bonus * g.size;
  bin_faces(s, n, a, g);
  if (with_hull) build_hull(g);
  else g.extreme = g.V;
  return g;
}

// Sweep scores for any number of directions: blocks of kBlock in parallel, each block's plate
// heights from the hull's vertices in one product.
std::vector<double> sweep_scores(const OrientationGeometry& g, const std::vector<Eigen::Vector3d>& dirs) {
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
OrientationCandidate exact_score(const OrientationGeometry& g, const Eigen::Vector3d& d, const std::string& origin) {
  const Eigen::VectorXd height = g.V * d;
  const double plate = height.minCoeff();
  OrientationCandidate c;
  c.direction = d;
  c.origin = origin;
  for (Eigen::Index f = 0; f < g.faces; ++f) {
    const auto i = static_cast<size_t>(f);
    const double nd = g.nx[i] * d.x() + g.ny[i] * d.y() + g.nz[i] * d.z();
    const FaceSupport support =
        face_support(height(g.F(f, 0)), height(g.F(f, 1)), height(g.F(f, 2)), plate, g.tolerance, nd + g.tau);
    if (support == FaceSupport::Plate) {
      c.contact_area += g.area[i];
    } else if (support == FaceSupport::Risky) {
      const double above_plate = g.cx[i] * d.x() + g.cy[i] * d.y() + g.cz[i] * d.z() - plate;
      c.shadow_volume += face_shadow(g.area[i], nd, above_plate);
      c.risky_area += g.area[i];
    }
  }
  c.score = c.shadow_volume - g.bonus_height * c.contact_area;
  return c;
}


int cube_cell(const Eigen::Vector3d& n, int R) {
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  const double scale = 1.0 / std::abs(n(axis));
  auto cell = [&](double t) { return std::clamp(static_cast<int>((t * scale + 1.0) * 0.5 * R), 0, R - 1); };
  return ((2 * axis + (n(axis) < 0 ? 1 : 0)) * R + cell(n((axis + 1) % 3))) * R + cell(n((axis + 2) % 3));
}

}  // namespace slim
