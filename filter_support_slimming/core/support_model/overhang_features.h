// The features of a part that a slicer supports, marked over the pixels and object layers they
// touch: what the support raster (support_raster.h) hands the sweep as contacts.
//
//   std::vector<PixelOverhang> features = overhang_features(surface, adjacency, grid, rule);
//
// Inputs
//   surface    #V by 3 positions (mm) in the print frame (+Z up, plate at z = 0), #F by 3
//              outward-oriented faces sharing their vertices.
//   adjacency  its faces' adjacency (face_adjacency.h).
//   grid       PixelGrid of the raster (support_raster.h).
//   rule       OverhangRule: the threshold and dense slopes (degrees from the horizontal), the
//              slicer's layers, and whether creases and tips count.
// Output: one PixelOverhang per pixel a feature touches (its closed square overlaps the feature's
// projection: conservative, so the slicer's stretching of any contact to a whole grid cell is
// exact), with the object layers the feature shows in there (layer k >= 1: its part between the
// slices of layers k - 1 and k; the voxel rasterizer of triangle_cells.h over pixels × layers) and
// whether it wants a dense interface. Unsorted. The features:
//   - a face the slicer sees overhang (face_overhang.h: less steep than rule.max_slope_deg, dense
//     when less steep than rule.dense_slope_deg, in a region that reaches far enough);
//   - around a region's edge, what the slicer adds by growing each layer's overhang back by one
//     layer's reach (layer_height / tan(max slope)) into the layer's own strip (the slice minus the slice below): the strip of a steeper
//     face below the edge (between the slices around it, within the reach), where the slice
//     below's outline lies;
//   - a bottom crease: an edge whose two faces both rise away from it, convex, less steep than
//     max_slope_deg, whose tip in the slice moves out of the layer below grown by
//     layer_height / tan(max slope) with square corners (the first slices of a keel are thin
//     islands with nothing below them); dense past the dense reach;
//   - a lowest vertex: below all its neighbours, on at least 3 faces; dense.
// A face or crease of a region shows in its top (bottom) layer only where its region, topping out
// (bottoming out) in that layer, reaches the slicer's margin past the slice below there
// (region_extent.h): a flare that ends just past a slice adds nothing to that layer.
// Cost: O(#F + pixels touched); faces, creases and tips found on the OpenMP threads in ranges
// gathered in order, so the output does not depend on the thread count.
#pragma once

#include <vector>

#include "core/support_model/support_raster.h"

namespace slim {

class FaceAdjacency;
std::vector<PixelOverhang> overhang_features(const Surface& surface, const FaceAdjacency& adjacency, const PixelGrid& grid,
                                             const OverhangRule& rule);

}  // namespace slim
