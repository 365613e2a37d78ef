// A tree of boxes over a surface's faces, for the distance from a point to the surface: the
// Hausdorff distance of the figures (surface_distance.h) asks it millions of times.
//
//   const FaceBoxTree tree(surface);
//   double d = tree.distance(p);            // to the nearest face, exactly
//   double d = tree.distance(p, &face);     // and which face (-1 for a surface without faces)
//
// Inputs: a surface (#V by 3 positions in mm, #F by 3 faces; indices checked by the caller), kept
//   by reference: it must outlive the tree, unchanged.
// Output: distance(p) = the smallest over the faces of |closest_on_triangle(p, face) - p| (mm), the
//   same value a scan of every face gives, bit for bit (ties: the lower face); HUGE_VAL without
//   faces.
// The boxes: the faces split at the median of their centroids along the longest side, down to 8
//   faces a leaf. A query visits the nearer child first and passes over a box farther than the
//   nearest face found, so a point far from the surface (a sample of a slimmed part that slid
//   further than the Hausdorff distance) costs about as little as one near it. A uniform grid's
//   shells of cells (uniform_grid.h) cost the cube of that distance in cells: at 1.1M faces the
//   Hausdorff distance took 2.7 s with them. Cost: O(#F log #F) to build, its subtrees as OpenMP
//   tasks (the same tree on any thread count); fewer than #F / 2 boxes.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/surface.h"

namespace slim {

class FaceBoxTree {
 public:
  explicit FaceBoxTree(const Surface& surface);
  double distance(const Eigen::Vector3d& p, int* face = nullptr) const;

 private:
  struct Node {
    Eigen::Vector3d lo, hi;  // the box of its faces
    int first = 0, count = 0;  // a leaf: faces order_[first, first + count)
    int left = -1, right = -1;  // an inner node: its two children
  };
  // Builds node `id` over the faces order_[first, first + count), its subtree in the nodes after it.
  void build(int id, int first, int count, std::vector<Eigen::Vector3d>& centroid);
  double box_distance(const Node& n, const Eigen::Vector3d& p) const;

  const Surface& s_;
  std::vector<int> order_;  // the faces, leaf by leaf
  std::vector<Node> nodes_;
};

}  // namespace slim
