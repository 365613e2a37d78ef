// The faces around every vertex and across every edge of a welded triangle mesh.
//
//   const FaceAdjacency adjacency(surface);            // or (faces, vertex count, every twin)
//   adjacency.faces_of(v)     the faces using vertex v, in increasing order
//   adjacency.across(f, k)    the face across face f's edge k, and its vertex opposite the edge
//
// Inputs
//   surface  #V by 3 positions, #F by 3 faces sharing their vertices (indices checked by the caller).
// Outputs
//   faces_of(v)   [begin, end) pointers into the faces around v.
//   across(f, k)  for edge k of face f (from F(f, k) to F(f, k + 1 mod 3)): {face, opposite}, the
//                 one other face that uses that edge and runs along it the other way (a manifold,
//                 consistently oriented edge) and its third vertex; {-1, -1} otherwise.
// Cost: O(#V + #F) to build (a counting sort by vertex); across() looks at the faces around one
// vertex (a few), so callers that need the twins of some edges only pay for those. With every
// twin asked for up front (a table of 3 #F, found on the OpenMP threads), across() is a lookup:
// for a caller that asks again and again (the support model on every iterate of one mesh).
#pragma once

#include <array>
#include <vector>

#include "core/geometry/surface.h"

namespace slim {

class FaceAdjacency {
 public:
  explicit FaceAdjacency(const Surface& surface);
  FaceAdjacency(const Triangles& faces, Eigen::Index vertices, bool every_twin);

  struct Twin {
    int face = -1, opposite = -1;
  };
  Twin across(int f, int k) const;
  bool has_every_twin() const { return !twins_.empty(); }  // across() is a lookup

  const int* faces_begin(int v) const { return vertex_face_.data() + vertex_begin_[v]; }
  const int* faces_end(int v) const { return vertex_face_.data() + vertex_begin_[v + 1]; }
  const std::array<int, 3>& face(int f) const { return tri_[f]; }

 private:
  std::vector<std::array<int, 3>> tri_;  // the faces row by row: the searches jump between faces
  std::vector<int> vertex_begin_, vertex_face_;
  std::vector<Twin> twins_;  // 3 #F when every twin was asked for, else empty
  Twin find_twin(int f, int k) const;
};

}  // namespace slim
