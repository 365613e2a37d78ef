// A uniform grid of cells over a box, each cell listing the items whose bounding boxes overlap it:
// the candidates near a point or a box, for the nearest-segment search (overhang_boundary.h), the
// tets around a point (tet_locator.h) and the face pairs that may intersect
// (surface_intersections.h).
//
//   UniformGrid grid(origin, cell, dims);
//   grid.fill(count, [&](int i, Eigen::Vector3d& lo, Eigen::Vector3d& hi) { ...item i's box... });
//   for (int item : grid.items(grid.index(grid.cell_of(p)))) ...
//
// Inputs
//   origin  the grid's low corner (3, any units).
//   cell    cell size along each axis (3, > 0, the same units).
//   dims    cells along each axis (3, >= 1). Cell (i, j, k) spans origin + (i, j, k) * cell to the
//           next corner; the outer cells reach on to infinity (points beyond the grid clamp).
//   fill    count items, each given by its axis-aligned box lo..hi.
// Outputs
//   cell_of(p)       the cell holding p, clamped to the grid; a NaN coordinate goes to cell 0, and
//                    nothing is cast out of int's range. Monotone in p, so a point inside an
//                    item's box always lies in one of the item's cells.
//   items(c)         the items listed in cell c (index(i, j, k)), ascending.
//   for_cells(lo, hi, visit)  visit(index) for every cell of the box, k outermost, i innermost.
//   nearest(p, distance, best) the item nearest to p, visiting shells of cells outwards.
//   entries(count, box_of)    the (cell, item) entries fill() would make, to choose dims first.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <Eigen/Core>

namespace slim {

class UniformGrid {
 public:
  struct Items {
    const int* first;
    const int* last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
  };

  UniformGrid() = default;
  UniformGrid(const Eigen::Vector3d& origin, const Eigen::Vector3d& cell, const Eigen::Vector3i& dims)
      : origin_(origin), cell_(cell), dims_(dims) {}

  // The cell index along `axis` of coordinate x.
  int axis_cell(double x, int axis) const {
    const double t = (x - origin_(axis)) / cell_(axis);
    if (!(t >= 0.0)) return 0;
    if (t >= static_cast<double>(dims_(axis) - 1)) return dims_(axis) - 1;
    return static_cast<int>(t);
  }
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const {
    return {axis_cell(p(0), 0), axis_cell(p(1), 1), axis_cell(p(2), 2)};
  }
  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) +
           static_cast<size_t>(dims_(0)) * (static_cast<size_t>(j) + static_cast<size_t>(dims_(1)) * static_cast<size_t>(k));
  }
  size_t index(const Eigen::Vector3i& c) const { return index(c(0), c(1), c(2)); }
  size_t cell_count() const {
    return static_cast<size_t>(dims_(0)) * static_cast<size_t>(dims_(1)) * static_cast<size_t>(dims_(2));
  }

  template <class Visit>
  void for_cells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Visit&& visit) const {
    const Eigen::Vector3i a = cell_of(lo), b = cell_of(hi);
    for (int k = a(2); k <= b(2); ++k)
      for (int j = a(1); j <= b(1); ++j)
        for (int i = a(0); i <= b(0); ++i) visit(index(i, j, k));
  }

  // How many (cell, item) entries fill() would make: a caller can choose a coarser grid first.
  template <class BoxOf>
  double entries(int count, BoxOf&& box_of) const {
    double total = 0.0;
    Eigen::Vector3d lo, hi;
    for (int i = 0; i < count; ++i) {
      box_of(i, lo, hi);
      const Eigen::Vector3i a = cell_of(lo), b = cell_of(hi);
      total += static_cast<double>(b(0) - a(0) + 1) * (b(1) - a(1) + 1) * (b(2) - a(2) + 1);
    }
    return total;
  }

  // Lists every item in the cells its box overlaps (two passes: count, then place), items in
  // ascending order within each cell.
  template <class BoxOf>
  void fill(int count, BoxOf&& box_of) {
    start_.assign(cell_count() + 1, 0);
    Eigen::Vector3d lo, hi;
    for (int i = 0; i < count; ++i) {
      box_of(i, lo, hi);
      for_cells(lo, hi, [&](size_t c) { ++start_[c + 1]; });
    }
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(start_.back());
    std::vector<size_t> next(start_.begin(), start_.end() - 1);
    for (int i = 0; i < count; ++i) {
      box_of(i, lo, hi);
      for_cells(lo, hi, [&](size_t c) { items_[next[c]++] = i; });
    }
  }

  Items items(size_t cell) const { return {items_.data() + start_[cell], items_.data() + start_[cell + 1]}; }

  // The item nearest to p by distance(item) (the exact distance from p to it), with that distance;
  // -1 and HUGE_VAL when the grid holds none (an item whose distance overflows is still an
  // answer, with that distance). Cells are visited in shells outwards from p's own,
  // until every item not yet seen lies in a cell beyond the nearest found (an item lies within its
  // cells' box); ties go to the lower item. Exact, whatever the cell size.
  template <class Distance>
  int nearest(const Eigen::Vector3d& p, Distance&& distance, double& best) const {
    best = HUGE_VAL;
    int best_item = -1;
    if (items_.empty()) return best_item;
    const Eigen::Vector3i centre = cell_of(p);
    const int max_shell = dims_.maxCoeff();
    for (int shell = 0; shell <= max_shell; ++shell) {
      Eigen::Vector3i from, to;
      for (int k = 0; k < 3; ++k) {
        from(k) = std::max(centre(k) - shell, 0);
        to(k) = std::min(centre(k) + shell, dims_(k) - 1);
      }
      auto visit = [&](int x, int y, int z) {
        // A cell farther than the nearest item found holds no nearer one: an item's nearest point
        // lies in one of its cells, and that cell is no farther than the item (the outer cells
        // reach on to infinity; a margin for the rounding of both distances).
        const Items cell = items(index(x, y, z));
        if (cell.first == cell.last) return;
        if (best_item >= 0 && cell_distance(p, Eigen::Vector3i(x, y, z)) > best * (1.0 + 1e-9)) return;
        for (int i : cell) {
          const double d = distance(i);
          // The first item seen is taken whatever its distance: one that overflows to infinity
          // (or is NaN) must not leave the answer undefined.
          if (best_item < 0 || d < best || (d == best && i < best_item)) {
            best = d;
            best_item = i;
          }
        }
      };
      // The cells of this shell only (the block's inner cells were visited in earlier shells):
      // whole planes where z is on the shell, whole rows where y is, else the row's two ends.
      for (int z = from(2); z <= to(2); ++z) {
        const bool z_ring = std::abs(z - centre(2)) == shell;
        for (int y = from(1); y <= to(1); ++y) {
          if (z_ring || std::abs(y - centre(1)) == shell) {
            for (int x = from(0); x <= to(0); ++x) visit(x, y, z);
            continue;
          }
          if (centre(0) - shell >= 0) visit(centre(0) - shell, y, z);
          if (shell > 0 && centre(0) + shell <= dims_(0) - 1) visit(centre(0) + shell, y, z);
        }
      }
      // Every item not seen yet lies in a cell outside the visited block, so at least as far as
      // the nearest of the block's faces that have cells beyond them.
      double unseen = HUGE_VAL;
      for (int k = 0; k < 3; ++k) {
        if (from(k) > 0) unseen = std::min(unseen, std::max(0.0, p(k) - (origin_(k) + from(k) * cell_(k))));
        if (to(k) < dims_(k) - 1) unseen = std::min(unseen, std::max(0.0, origin_(k) + (to(k) + 1) * cell_(k) - p(k)));
      }
      if (best < unseen) break;
    }
    return best_item;
  }

  // The distance from p to cell c's box (an outer cell reaching on to infinity).
  double cell_distance(const Eigen::Vector3d& p, const Eigen::Vector3i& c) const {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double lo = origin_(k) + c(k) * cell_(k), hi = origin_(k) + (c(k) + 1) * cell_(k);
      double gap = 0.0;
      if (c(k) > 0 && p(k) < lo) gap = lo - p(k);
      if (c(k) < dims_(k) - 1 && p(k) > hi) gap = p(k) - hi;
      d2 += gap * gap;
    }
    return std::sqrt(d2);
  }

  const Eigen::Vector3d& origin() const { return origin_; }
  const Eigen::Vector3d& cell_size() const { return cell_; }
  const Eigen::Vector3i& dims() const { return dims_; }

 private:
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d cell_ = Eigen::Vector3d::Ones();
  Eigen::Vector3i dims_ = Eigen::Vector3i::Ones();
  std::vector<size_t> start_;
  std::vector<int> items_;
};

}  // namespace slim
