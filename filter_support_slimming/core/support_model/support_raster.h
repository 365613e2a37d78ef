// The part seen along the print direction, pixel by pixel: what the support model sweeps.
//
//   SupportRaster build_support_raster(surface, grid, rule)
//   SupportRaster build_support_raster(surface, adjacency, grid, rule)   // adjacency kept by the caller
//
// Inputs
//   surface  #V by 3 positions (mm) in the print frame (+Z up), #F by 3 outward-oriented faces
//            sharing their vertices. The plate is wherever the caller says (the raster only
//            reads z values).
//   grid     PixelGrid: nx by ny square pixels of side `pixel` mm, pixel (i, j) covering
//            [x0 + i·pixel, x0 + (i+1)·pixel) × [y0 + j·pixel, ...). It should cover the part.
//   rule     OverhangRule: which features need support (slopes from the horizontal, degrees).
// Output (SupportRaster)
//   spans     for every pixel (index i + nx·j), the solid intervals [bottom, top] (mm) of the
//             vertical ray through its centre, sorted upwards: where the faces the ray crosses
//             wind around it (nonzero rule, so an inside-out part reads the same). Rasterised
//             watertight: a centre on a shared edge or vertex is counted by one face only.
//             With rule.slices: where the slices at the slicer's slice heights (first_layer / 2,
//             then first_layer + (k - 1/2) layer) wind around the centre, each run of layers
//             k0..k1 as [slice(k0) - layer / 4, slice(k1) + layer / 4].
//   overhangs the features the slicer supports, per pixel they touch, with the object layers they
//             show in there and whether they want a dense interface: overhanging faces, bottom
//             creases and lowest points (overhang_features.h), and with rule.slices the slices
//             above lost contours (slice_raster.h). Sorted by pixel, then layers; a pixel may
//             carry several overhangs (one per feature touching it).
// Cost: O(#F + #pixels touched); with rule.slices also O(segments + pixels × layers). Deterministic:
// the same on any thread count.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

struct PixelGrid {
  double x0 = 0.0, y0 = 0.0;  // mm, lower-left corner of pixel (0, 0)
  double pixel = 1.0;         // mm, > 0
  int nx = 0, ny = 0;         // pixels along x and y
  int count() const { return nx * ny; }
};

struct OverhangRule {
  double max_slope_deg = 46.0;    // features less steep than this (from the horizontal) overhang
  double dense_slope_deg = 36.5;  // overhangs less steep than this want a dense interface
  double first_layer_height = 0.2;  // mm: the slicer's layers, to say in which one a feature shows
  double layer_height = 0.2;      // mm; also: a region of overhanging faces narrower than
                                  // layer_height / tan(max_slope_deg) is not seen by the slicer
  bool creases = true;            // bottom creases overhang (keels)
  bool tips = true;               // lowest vertices overhang
  // How the solid is read. Along the rays (false): the faces each ray crosses, nonzero winding,
  // exact for a closed mesh. Slice by slice (true), as the slicer cuts the part (layer_slices.h):
  // for an open mesh, whose open chains the slicer closes across gaps up to slice_max_gap and
  // otherwise drops; a dropped contour empties its slice, and the slicer supports the slice above
  // it as a flat overhang. On a closed mesh both readings give the same spans.
  bool slices = false;
  double slice_max_gap = 2.0;     // mm (PrusaSlicer 2.5)
};

struct SolidSpan {
  double bottom = 0.0, top = 0.0;  // mm
};

struct PixelOverhang {
  int pixel = 0;
  int layer_low = 0, layer_high = 0;  // the object layers the feature shows in over the pixel
  bool dense = false;
};

struct SupportRaster {
  PixelGrid grid;
  std::vector<int> span_begin;   // #pixels + 1 offsets into spans
  std::vector<SolidSpan> spans;  // per pixel, sorted upwards, disjoint
  std::vector<PixelOverhang> overhangs;  // sorted by pixel, then z_low
};

class FaceAdjacency;
SupportRaster build_support_raster(const Surface& surface, const PixelGrid& grid, const OverhangRule& rule);
// The same with the faces' adjacency (face_adjacency.h) of surface's faces given: a caller that
// rasterises many shapes of one mesh finds it once.
SupportRaster build_support_raster(const Surface& surface, const FaceAdjacency& adjacency, const PixelGrid& grid,
                                   const OverhangRule& rule);

}  // namespace slim
