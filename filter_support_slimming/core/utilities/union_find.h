// Union-find (disjoint sets) over the integers 0 .. n-1: connected components of a graph given
// edge by edge.
//
//   UnionFind sets(n);   sets.join(a, b);   sets.find(v)
//
// Inputs:  n >= 0 elements; join(a, b) for 0 <= a, b < n, in any order.
// Outputs: find(v), the representative of v's set: always the lowest element of that set (the
//          smaller root wins every join), so the representatives, and anything numbered from
//          them, do not depend on the order of the joins.
// Path halving keeps every find near O(1) amortised.
#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

namespace slim {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }

  int find(int v) {
    while (parent_[static_cast<size_t>(v)] != v) {
      parent_[static_cast<size_t>(v)] = parent_[static_cast<size_t>(parent_[static_cast<size_t>(v)])];
      v = parent_[static_cast<size_t>(v)];
    }
    return v;
  }

  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace slim
