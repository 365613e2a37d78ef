// Which faces a slicer sees overhang, face by face: the first step of the support model's
// features (overhang_features.h), and the regions whose extent region_extent.h walks.
//
//   std::vector<FaceOverhang> faces = face_overhangs(surface, adjacency, rule);
//
// Inputs
//   surface    #V by 3 positions (mm) in the print frame (+Z up), #F by 3 outward-oriented faces
//              sharing their vertices.
//   adjacency  its FaceAdjacency.
//   rule       OverhangRule (support_raster.h): the threshold and dense slopes (degrees from the
//              horizontal) and the layer height (mm).
// Output: one FaceOverhang per face. A face less steep than the threshold overhangs (densely when
// less steep than the dense slope), unless its connected region of such faces reaches less than
// half a layer's reach (layer_height / tan(slope)) beyond the layer below (a lip or a fold). From
// one layer to the next a region reaches beyond the layer below by its own width w and then by
// what the faces around it add over the rest of the layer: the surface descends from the region
// over those faces (their mean horizontal run per height, cot s, length-weighted over the
// region's outline; walls add nothing), so the reach is w + (layer - w tan(slope)) cot s. The
// width of a region is 2 × area / outline of its projection (the width of a strip, the radius of
// a disc), which understates how far an irregular patch reaches; so a region is dropped only when
// its reach stays under half of layer / tan(max slope): a thin lip on a wall (the slicer lays
// nothing under it), not a patch of a scan's surface just below the threshold among faces just
// above it (the slicer supports those). A face of a region is on its edge when a side has no
// overhanging face.
// Cost: O(#F); the slopes on the OpenMP threads, the regions in one pass.
#pragma once

#include <vector>

#include "core/geometry/surface.h"
#include "core/support_model/support_raster.h"

namespace slim {

class FaceAdjacency;

struct FaceOverhang {
  enum class Kind : unsigned char {
    None,      // the slicer sees no overhang here
    Overhang,  // supported with sparse lines
    Dense      // less steep than the dense slope: a dense interface under it
  };
  Kind kind = Kind::None;
  bool region_edge = false;  // overhangs, and a side of it has no overhanging face
  bool overhangs() const { return kind != Kind::None; }
  bool dense() const { return kind == Kind::Dense; }
};

std::vector<FaceOverhang> face_overhangs(const Surface& surface, const FaceAdjacency& adjacency, const OverhangRule& rule);

// How far a slice must reach past the slice below to overhang there (mm): one layer's run at the
// threshold slope.
double slicer_margin(const OverhangRule& rule);

}  // namespace slim
