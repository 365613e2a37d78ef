// The faces around every vertex and across every edge of a welded triangle mesh.
//
//   FaceAdjacency adjacency = face_adjacency(surface);
//
// Inputs
//   surface  #V by 3 positions, #F by 3 faces sharing their vertices (indices checked by the caller).
// Outputs (FaceAdjacency)
//   vertex_begin  #V + 1 offsets into vertex_face: the faces using vertex v are
//                 vertex_face[vertex_begin[v] .. vertex_begin[v + 1]), in increasing order.
//   across        3 #F: across[3 f + k] is the face on the other side of face f's edge k (from
//                 F(f, k) to F(f, k + 1 mod 3)) when exactly one other face uses that edge and runs
//                 along it the other way (a manifold, consistently oriented edge); -1 otherwise.
//   opposite      3 #F: that face's vertex opposite the edge; -1 with across.
// Cost: O(#F) (a counting sort by vertex, then a look at the few faces around each vertex).
#pragma once

#include <vector>

#include "core/surface.h"

namespace slim {

struct FaceAdjacency {
  std::vector<int> vertex_begin, vertex_face, across, opposite;
};

FaceAdjacency face_adjacency(const Surface& surface);

}  // namespace slim
