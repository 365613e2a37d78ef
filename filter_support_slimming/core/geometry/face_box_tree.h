// A tree of boxes over a surface's faces, for the distance from a point to the surface: the
// Hausdorff distance of the figures (surface_distance.h) asks it millions of times.
//
//   const FaceBoxTree tree(surface);
//   double d = tree.distance(p);            // to the nearest face, exactly
//   double d = tree.distance(p, &face);     // and which face (-1 for a surface without faces)
//   const FaceBoxTree moved_tree(tree, moved);  // the same faces moved: the same splits, refit
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
//   shells of cells (uniform_grid.h) cost the cube of that distance in cells, too slow for the
//   Hausdorff distance of a million-face part (docs/history/speed-earlier.md). Cost: O(#F log #F)
//   to build, its subtrees as OpenMP tasks (the same tree on any thread count); fewer than #F / 2
//   boxes.
// Refit (a surface with the same faces, other positions: the same mesh moved): the splits are
//   kept and only the boxes made anew, leaves first, in O(#F). The distances are as exact as on a
//   tree of its own; a query only visits more boxes where the faces moved far from where they
//   were split. A slimmed part's figures use it for the result (surface_distance.h).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

class FaceBoxTree {
 public:
  explicit FaceBoxTree(const Surface& surface);
  // The splits of `shape` over `moved`, which has its surface's faces (checked by the caller).
  FaceBoxTree(const FaceBoxTree& shape, const Surface& moved);
  double distance(const Eigen::Vector3d& p, int* face = nullptr) const;

 private:
  struct Node {
    Eigen::Vector3d lo, hi;  // the box of its faces
    int first = 0, count = 0;  // a leaf: faces order_[first, first + count)
    int left = -1, right = -1;  // an inner node: its two children
  };
  // Builds node `id` over the faces order_[first, first + count), its subtree in the nodes after it.
  void build(int id, int first, int count, std::vector<Eigen::Vector3d>& centroid);
  // The box of leaf n's faces; of inner node n's two children's boxes.
  void fit_leaf(Node& n) const;
  void fit_inner(Node& n) const;
  double box_distance(const Node& n, const Eigen::Vector3d& p) const;

  const Surface& s_;
  std::vector<int> order_;  // the faces, leaf by leaf
  std::vector<Node> nodes_;
};

}  // namespace slim
