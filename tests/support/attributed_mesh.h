// The mesh of the "what goes in comes out" tests: every kind of vertex list a user's
// file may hold, with the attributes files carry beside the positions.
//
// attributed_mesh() -> AttributedMesh
//   surface  two boxes that share one corner vertex (a non-manifold vertex, one index), the upper
//            one overhanging; a third box above, touching the second at a corner through a vertex
//            of its own at the same point (coincident, another index); one face of the lower box
//            using a copy of its corner in place of the original (a duplicate: a seam); a copy of
//            a used vertex that no face uses; and a vertex beside the boxes that no face uses.
//   colour   #V by 4 RGBA, no two vertices alike;  texcoord #V by 2, multiples of 1/64 (exact in
//            float);  normal #V by 3, unit, not the geometric ones (a file's own).
//   the indices of the special vertices, for the tests to look at.
// write_attributed_ply(path, m) writes it as an ASCII PLY (x y z nx ny nz red green blue alpha
//   texture_u texture_v), by hand, not through the code under test.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim::test {

struct AttributedMesh {
  Surface surface;
  Eigen::Matrix<unsigned char, Eigen::Dynamic, 4, Eigen::RowMajor> colour;
  Eigen::Matrix<double, Eigen::Dynamic, 2> texcoord;
  Points normal;
  int shared_corner = -1;        // the non-manifold vertex of the two lower boxes
  int coincident_corner = -1;    // the top box's own vertex at a corner of the middle box
  int seam_copy = -1, seam_original = -1;
  int unreferenced_copy = -1;    // a copy of seam_original that no face uses
  int unreferenced_apart = -1;   // beside the boxes, in no face
};

AttributedMesh attributed_mesh();

void write_attributed_ply(const std::string& path, const AttributedMesh& m);

}  // namespace slim::test
