// How far each region of overhanging faces reaches up and down from each of its vertices, and so
// in which layers a feature of it shows: a slicer sees an overhang in a layer only where the slice
// reaches past the slice below by its margin (layer / tan(threshold)), so a region that begins or
// ends just past a slice shows nothing in that layer. A foot whose rounded bottom flares out within
// the first two slices gets no contact under the first layer; the same flare ending just past the
// second slice does not push one there.
//
//   std::vector<RegionExtent> extents = region_extents(surface, adjacency, in_region);
//   ShownHeights shown = shown_heights(z_low, z_high, run, extent, planes, margin);
//
// Inputs
//   surface    #V by 3 positions (mm) in the print frame (+Z up), #F by 3 faces sharing vertices.
//   adjacency  its FaceAdjacency (the faces around each vertex).
//   in_region  per face: nonzero for a face of a region of overhanging faces.
//   z_low, z_high  the lowest and highest point (mm) of a feature of a region (a face, a crease).
//   run        the feature's horizontal run per height (mm/mm; cot of its slope; inf when level).
//   extent     the feature's RegionExtent: the highest top and lowest bottom among its vertices'.
//   planes     SlicePlanes: the slicer's first layer and layer height (mm).
//   margin     mm: how far a slice must reach past the slice below to overhang there.
// Outputs
//   RegionExtent per vertex: top and bottom (mm), the highest and lowest points reached from the
//   vertex going up (down) along its regions' faces, and there run_above (run_below), the largest
//   horizontal run per height of the faces outside the regions that look down and rise from it
//   (fall from it): the steeper wall the region turns into, 0 where there is none. Off the regions
//   top = -inf and bottom = +inf.
//   ShownHeights [low, high] (mm): the part of the feature to mark. Its top layer (the slices
//   around z_high) is left out when the region tops out in it and the surface there, from the
//   slice below to the slice above (wall below, region, wall above), reaches less than margin; so
//   is its bottom layer when the region bottoms out in it. Layers below the second never matter
//   (their contacts would sit below the first layer) and are kept.
// Cost: O(#F + #V log #V) for the extents (a sort of the regions' vertices by height); O(1) per
// feature.
#pragma once

#include <cmath>
#include <vector>

#include "core/geometry/surface.h"

namespace slim {

class FaceAdjacency;

struct RegionExtent {
  double top = -INFINITY, run_above = 0.0;
  double bottom = INFINITY, run_below = 0.0;
};

struct SlicePlanes {
  double first_height = 0.2;  // mm
  double height = 0.2;        // mm
  // Layer k >= 1 lies between the slices of layers k - 1 and k, at first + (k - 1/2) height.
  double layer_of(double z) const { return std::floor((z - first_height) / height + 1.5); }
  double slice_z(double k) const { return first_height + (k - 0.5) * height; }
};

struct ShownHeights {
  double low = -INFINITY, high = INFINITY;  // mm
};

std::vector<RegionExtent> region_extents(const Surface& surface, const FaceAdjacency& adjacency,
                                         const std::vector<char>& in_region);

// The extent of a feature whose vertices are given: the highest top and lowest bottom among them.
template <class Vertices>
RegionExtent feature_extent(const std::vector<RegionExtent>& extents, const Vertices& vertices) {
  RegionExtent out;
  for (int v : vertices) {
    const RegionExtent& e = extents[static_cast<size_t>(v)];
    if (e.top > out.top) out.top = e.top, out.run_above = e.run_above;
    if (e.bottom < out.bottom) out.bottom = e.bottom, out.run_below = e.run_below;
  }
  return out;
}

ShownHeights shown_heights(double z_low, double z_high, double run, const RegionExtent& extent, const SlicePlanes& planes,
                           double margin);

}  // namespace slim
