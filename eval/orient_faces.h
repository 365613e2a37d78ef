// Faces turned so that neighbours agree, for meshes that arrive with a few flipped faces (game
// and viewer test models often do). The judge refuses such meshes, as the CLI does; the corpus
// mends them once, with VCG's OrientCoherentlyMesh.
#pragma once

#include "core/geometry/surface.h"

namespace slim::eval {

struct OrientedFaces {
  Surface surface;       // same vertices; some faces with their 2nd and 3rd vertex swapped
  long flipped = 0;      // faces turned over
  long dropped = 0;      // faces that name one vertex twice, left out
  bool orientable = true;  // false: a non-orientable piece (a Moebius strip) could not be fixed
};

// Every connected piece (faces sharing edges) is oriented coherently from one of its faces, then
// turned over as a whole when it encloses a negative volume. A face that names one vertex twice
// has no side to agree on (and VCG's orientation walk reads it as a fold it cannot mend): it is
// left out. Vertices stay; the other faces keep their order.
OrientedFaces orient_faces(const Surface& s);

}  // namespace slim::eval
