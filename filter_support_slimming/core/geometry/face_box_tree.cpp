#include "core/geometry/face_box_tree.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/geometry/closest_on_triangle.h"

namespace slim {
namespace {
constexpr int kLeafFaces = 8;
// Subtrees of at least this many faces are built as OpenMP tasks.
constexpr int kTaskFaces = 1 << 14;

// The nodes of a subtree over `count` faces: its shape depends on the count alone, so each
// subtree owns a range of nodes known before it is built (pre-order: a node, its left subtree,
// its right subtree), and subtrees can be built apart into one vector.
int subtree_nodes(int count) {
  return count <= kLeafFaces ? 1 : 1 + subtree_nodes(count / 2) + subtree_nodes(count - count / 2);
}
}  // namespace

FaceBoxTree::FaceBoxTree(const Surface& surface) : s_(surface) {
  const int faces = static_cast<int>(surface.F.rows());
  order_.resize(static_cast<size_t>(faces));
  std::vector<Eigen::Vector3d> centroid(static_cast<size_t>(faces));
#pragma omp parallel for schedule(static)
  for (int f = 0; f < faces; ++f) {
    order_[static_cast<size_t>(f)] = f;
    centroid[static_cast<size_t>(f)] =
        (surface.V.row(surface.F(f, 0)) + surface.V.row(surface.F(f, 1)) + surface.V.row(surface.F(f, 2))).transpose() / 3.0;
  }
  if (faces == 0) return;
  nodes_.resize(static_cast<size_t>(subtree_nodes(faces)));
  // The tree is the same on any thread count: each subtree's faces, split and nodes are fixed
  // before it is built; the tasks only share out the work.
#pragma omp parallel
#pragma omp single
  build(0, 0, faces, centroid);
}

FaceBoxTree::FaceBoxTree(const FaceBoxTree& shape, const Surface& moved)
    : s_(moved), order_(shape.order_), nodes_(shape.nodes_) {
  const auto count = static_cast<long>(nodes_.size());
#pragma omp parallel for schedule(static)
  for (long id = 0; id < count; ++id)
    if (nodes_[static_cast<size_t>(id)].left < 0) fit_leaf(nodes_[static_cast<size_t>(id)]);
  // Pre-order: a node's children come after it, so backwards every child is fitted before it.
  for (long id = count - 1; id >= 0; --id) {
    Node& n = nodes_[static_cast<size_t>(id)];
    if (n.left >= 0) fit_inner(n);
  }
}

void FaceBoxTree::fit_leaf(Node& n) const {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (int i = n.first; i < n.first + n.count; ++i)
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(s_.V.row(s_.F(order_[static_cast<size_t>(i)], k)).transpose());
      hi = hi.cwiseMax(s_.V.row(s_.F(order_[static_cast<size_t>(i)], k)).transpose());
    }
  n.lo = lo, n.hi = hi;
}

void FaceBoxTree::fit_inner(Node& n) const {
  const Node &a = nodes_[static_cast<size_t>(n.left)], &b = nodes_[static_cast<size_t>(n.right)];
  n.lo = a.lo.cwiseMin(b.lo);
  n.hi = a.hi.cwiseMax(b.hi);
}

void FaceBoxTree::build(int id, int first, int count, std::vector<Eigen::Vector3d>& centroid) {
  Node& n = nodes_[static_cast<size_t>(id)];
  if (count <= kLeafFaces) {
    n.first = first, n.count = count;
    fit_leaf(n);
    return;
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(centroid[static_cast<size_t>(order_[static_cast<size_t>(i)])]);
    hi = hi.cwiseMax(centroid[static_cast<size_t>(order_[static_cast<size_t>(i)])]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const auto begin = order_.begin() + first, middle = begin + count / 2, end = begin + count;
  // Ties by face index: the split, and so the tree, is the same on every run.
  std::nth_element(begin, middle, end, [&](int a, int b) {
    const double x = centroid[static_cast<size_t>(a)](axis), y = centroid[static_cast<size_t>(b)](axis);
    return x < y || (x == y && a < b);
  });
  n.left = id + 1;
  n.right = id + 1 + subtree_nodes(count / 2);
#pragma omp task default(shared) if (count >= kTaskFaces)
  build(n.left, first, count / 2, centroid);
  build(n.right, first + count / 2, count - count / 2, centroid);
#pragma omp taskwait
  fit_inner(n);
}

double FaceBoxTree::box_distance(const Node& n, const Eigen::Vector3d& p) const {
  return (p.cwiseMax(n.lo).cwiseMin(n.hi) - p).norm();
}

double FaceBoxTree::distance(const Eigen::Vector3d& p, int* face) const {
  double best = HUGE_VAL;
  int best_face = -1;
  if (nodes_.empty()) {
    if (face) *face = best_face;
    return best;
  }
  // A box no nearer than the nearest face found holds no nearer face; the margin covers the
  // rounding of the two distances (a face at exactly that distance, of a lower index, is still seen).
  auto far = [&](const Node& n) { return best_face >= 0 && box_distance(n, p) > best * (1.0 + 1e-9); };
  std::array<int, 128> stack;  // one node a level plus one: the tree is about log2(#F / 8) deep
  int top = 0;
  stack[static_cast<size_t>(top++)] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<size_t>(stack[static_cast<size_t>(--top)])];
    if (far(n)) continue;
    if (n.left < 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        const int f = order_[static_cast<size_t>(i)];
        const double d = (closest_on_triangle(p, s_.V.row(s_.F(f, 0)).transpose(), s_.V.row(s_.F(f, 1)).transpose(),
                                              s_.V.row(s_.F(f, 2)).transpose()) - p).norm();
        if (best_face < 0 || d < best || (d == best && f < best_face)) best = d, best_face = f;
      }
      continue;
    }
    const Node &a = nodes_[static_cast<size_t>(n.left)], &b = nodes_[static_cast<size_t>(n.right)];
    const bool left_first = box_distance(a, p) <= box_distance(b, p);
    stack[static_cast<size_t>(top++)] = left_first ? n.right : n.left;  // the nearer on top: visited first
    stack[static_cast<size_t>(top++)] = left_first ? n.left : n.right;
  }
  if (face) *face = best_face;
  return best;
}

}  // namespace slim
