// The surface the core computes on when a mesh's vertex list repeats a position.
//
// Files and MeshLab layers often hold several vertices at exactly the same point: texture or
// colour seams, parts exported piece by piece, two solids touching at a corner. Faces that meet
// there then share no vertex index, so the topology seen through indices (edge_topology,
// inside_out, the pieces of a rigid feature, the closed surface TetGen needs) is the file's
// bookkeeping, not the shape. The welded view merges vertices whose three coordinates are equal
// (bit for bit, no tolerance), computes on that, and maps every result back to each copy. The
// caller's own vertex list is never changed: what goes in comes out, in the same order.
//
// weld_coincident(s) -> WeldedView
//   s        Surface{V #V by 3, F #F by 3}. With a non-finite coordinate anywhere, or an index
//            outside V, nothing is merged (the view is s itself), so that check_surface names
//            the input's own vertex or face.
// WeldedView
//   surface      V #W by 3: the first copy of each position, in the order of the input's first
//                copies (so W <= #V, and the input's vertices before its first repeated copy keep
//                their index); F #F by 3: the input's faces, in order, pointing at view vertices.
//                Unreferenced vertices stay (a lone one as itself, a coincident one merged).
//   view_vertex  #V: the view vertex of each input vertex.
//   merged()     #V - W: how many input vertices are copies of an earlier one.
//   to_input(X)  #W rows of per-vertex results (positions #W by 3, displacements #W) -> #V rows,
//                row i being X.row(view_vertex[i]). Per-face results need no mapping: the faces
//                are the input's, in its order.
//   positions_to_input(V, after)  V: the input's #V by 3 positions; after: the view's #W by 3
//                positions after a run. A vertex whose view vertex did not move keeps its own
//                coordinates bit for bit (-0 stays -0, though it merged with +0); the others get
//                the view's new position, so all copies of a point stay together.
// Messages the core gives about the view name its faces as the input does, but its vertices by
// view index; vertex_number_note(message) is a clause that says so, for the end of a message that
// names a vertex or an edge, when anything was merged ("" otherwise).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

struct WeldedView {
  Surface surface;
  std::vector<int> view_vertex;

  Eigen::Index merged() const { return static_cast<Eigen::Index>(view_vertex.size()) - surface.V.rows(); }

  template <class Derived>
  Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, Derived::ColsAtCompileTime> to_input(
      const Eigen::MatrixBase<Derived>& view_rows) const {
    Eigen::Matrix<typename Derived::Scalar, Eigen::Dynamic, Derived::ColsAtCompileTime> out(
        static_cast<Eigen::Index>(view_vertex.size()), view_rows.cols());
    for (size_t i = 0; i < view_vertex.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = view_rows.row(view_vertex[i]);
    return out;
  }

  Points positions_to_input(const Points& input_V, const Points& view_after) const;

  std::string vertex_number_note(const std::string& message) const;
};

WeldedView weld_coincident(const Surface& s);

}  // namespace slim
