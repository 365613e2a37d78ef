#include "core/geometry/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/geometry/closest_on_triangle.h"
#include "core/geometry/face_box_tree.h"

namespace slim {

namespace {

Eigen::Vector3d corner(const Surface& s, Eigen::Index f, int k) { return s.V.row(s.F(f, k)).transpose(); }

// The samples of one vertex (id < #V) or face (id = #V + f) of s: the vertex, or the face's
// centroid and its three edge midpoints. Returns their count. samples() makes them the same way.
int unit_samples(const Surface& s, Eigen::Index id, Eigen::Vector3d out[4]) {
  if (id < s.V.rows()) {
    out[0] = s.V.row(id).transpose();
    return 1;
  }
  const Eigen::Index f = id - s.V.rows();
  const Eigen::Vector3d a = corner(s, f, 0), b = corner(s, f, 1), c = corner(s, f, 2);
  out[0] = (a + b + c) / 3.0;
  out[1] = 0.5 * (a + b);
  out[2] = 0.5 * (b + c);
  out[3] = 0.5 * (c + a);
  return 4;
}

// The samples of a surface: the vertices that faces use (a vertex of no face is no part of the
// surface, and the moved search's bound, how far a sample moved, holds only on the surface), face
// centroids, edge midpoints (each edge once per face).
Points samples(const Surface& s) {
  const std::vector<Eigen::Index> vertices = face_vertices(s);
  const auto count = static_cast<Eigen::Index>(vertices.size());
  Points P(count + 4 * s.F.rows(), 3);
  for (Eigen::Index k = 0; k < count; ++k) P.row(k) = s.V.row(vertices[static_cast<size_t>(k)]);
  Eigen::Index row = count;
  Eigen::Vector3d face[4];
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    unit_samples(s, s.V.rows() + f, face);
    for (const Eigen::Vector3d& p : face) P.row(row++) = p.transpose();
  }
  return P;
}

// The largest and mean distance from the samples of `from` to the surface `to`.
void one_way(const Surface& from, const Surface& to, double& largest, double& mean) {
  const Points P = samples(from);
  const FaceBoxTree tree(to);
  const Eigen::Index n = P.rows();
  std::vector<double> d(static_cast<size_t>(n));
#pragma omp parallel for schedule(dynamic, 1024)
  for (Eigen::Index i = 0; i < n; ++i) d[static_cast<size_t>(i)] = tree.distance(P.row(i).transpose());
  largest = n > 0 ? *std::max_element(d.begin(), d.end()) : 0.0;
  double sum = 0.0;
  for (double x : d) sum += x;  // in order: the same bits on any thread count
  mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
}

// The moved search's units, in the order it visits them: a vertex that faces use (its own sample)
// or a face (its centroid and edge midpoints), each with how far its samples moved at most: the
// vertex's own move; for a face, the largest move of its corners, as an average of points moves
// no further than the furthest of them. Vertices are ids [0, #V), face f is #V + f.
struct Unit {
  double bound;
  Eigen::Index id;
};

std::vector<Unit> units_by_move(const Surface& a, const Surface& b) {
  const Eigen::VectorXd moved = (a.V - b.V).rowwise().norm();
  const std::vector<Eigen::Index> vertices = face_vertices(a);
  std::vector<Unit> units(vertices.size() + static_cast<size_t>(a.F.rows()));
  for (size_t k = 0; k < vertices.size(); ++k) units[k] = {moved(vertices[k]), vertices[k]};
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    units[vertices.size() + static_cast<size_t>(f)] = {
        std::max({moved(a.F(f, 0)), moved(a.F(f, 1)), moved(a.F(f, 2))}), a.V.rows() + f};
  return units;
}

// The largest distance from the samples of the given units of `from` to the surface of `tree`
// (`to`: the same mesh moved), or `largest` if more: the units in order, in blocks, until a block
// starts at no more than the largest distance found; within a unit only the samples that moved
// further than that (a sample's moved copy lies on `to`, so its distance is at most how far it
// moved). The largest of exact distances: the same value on any thread count.
double largest_one_way(const Surface& from, const Surface& to, const FaceBoxTree& tree, const std::vector<Unit>& order,
                       double largest) {
  constexpr size_t kBlock = 4096;
  for (size_t start = 0; start < order.size() && order[start].bound > largest; start += kBlock) {
    const size_t end = std::min(order.size(), start + kBlock);
    std::vector<double> d(end - start, 0.0);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t k = start; k < end; ++k) {
      if (!(order[k].bound > largest)) continue;
      Eigen::Vector3d p[4], q[4];
      const int n = unit_samples(from, order[k].id, p);
      unit_samples(to, order[k].id, q);
      for (int i = 0; i < n; ++i)
        if ((p[i] - q[i]).norm() > largest) d[k - start] = std::max(d[k - start], tree.distance(p[i]));
    }
    for (double x : d) largest = std::max(largest, x);
  }
  return largest;
}

}  // namespace

SurfaceDistance surface_distance(const Surface& a, const Surface& b) {
  check_surface(a);
  check_surface(b);
  SurfaceDistance d;
  if (a.F.rows() == 0 || b.F.rows() == 0) return d;
  one_way(a, b, d.a_to_b_max_mm, d.a_to_b_mean_mm);
  one_way(b, a, d.b_to_a_max_mm, d.b_to_a_mean_mm);
  d.hausdorff_mm = std::max(d.a_to_b_max_mm, d.b_to_a_max_mm);
  return d;
}

double hausdorff_of_moved(const Surface& a, const Surface& b) {
  check_surface(a);
  check_surface(b);
  if (a.V.rows() != b.V.rows() || a.F.rows() != b.F.rows() || a.F != b.F)
    throw std::invalid_argument("Hausdorff distance of a moved mesh: the two surfaces are not one mesh");
  if (a.F.rows() == 0) return 0.0;
  const FaceBoxTree tree_a(a), tree_b(tree_a, b);  // b: a's faces moved, on a's splits
  std::vector<Unit> units = units_by_move(a, b);
  // Both ways on the units that moved most, then both ways on the rest that moved further than
  // the distance found: sorting all of them took as long as the searches. Each search starts from
  // the distance found before it, both ways: only a larger one can change the answer.
  auto further = [](const Unit& x, const Unit& y) { return x.bound > y.bound || (x.bound == y.bound && x.id < y.id); };
  const auto first = static_cast<std::ptrdiff_t>(std::min<size_t>(4096, units.size()));
  std::partial_sort(units.begin(), units.begin() + first, units.end(), further);
  const std::vector<Unit> head(units.begin(), units.begin() + first);
  double largest = largest_one_way(b, a, tree_a, head, largest_one_way(a, b, tree_b, head, 0.0));
  std::vector<Unit> rest;
  std::copy_if(units.begin() + first, units.end(), std::back_inserter(rest), [&](const Unit& u) { return u.bound > largest; });
  std::sort(rest.begin(), rest.end(), further);
  largest = largest_one_way(a, b, tree_b, rest, largest);
  return largest_one_way(b, a, tree_a, rest, largest);
}

}  // namespace slim
