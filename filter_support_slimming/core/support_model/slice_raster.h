// The solid of a part read slice by slice, as the slicer cuts it: the support raster's reading of
// an open mesh (support_raster.h, OverhangRule::slices).
//
//   rasterize_slices(surface, adjacency, rule, raster);
//
// Inputs
//   surface    #V by 3 positions (mm) in the print frame (+Z up, plate at z = 0), #F by 3 faces
//              sharing their vertices; it may have holes.
//   adjacency  its faces' adjacency (face_adjacency.h).
//   rule       the slicer's layers (first_layer_height, layer_height) and slice_max_gap.
//   raster     its grid set; span_begin and spans are replaced, overhangs appended to.
// Output, in raster:
//   spans      per pixel, the runs of slices that wind around its centre (nonzero rule): slices at
//              the slicer's slice heights, slice(0) = first_layer / 2 and slice(k) = first_layer +
//              (k - 1/2) · layer, cut by slice_layers (layer_slices.h) with open chains closed
//              across gaps up to slice_max_gap and the rest dropped; a run k0..k1 is the span
//              [slice(k0) - layer / 4, slice(k1) + layer / 4], so the sweep reads exactly those
//              layers as solid.
//   overhangs  a dense overhang at layer k on every pixel that slice k fills, slice k - 1 does not,
//              and slice k - 1 would with its dropped chains closed by a straight line: the slicer
//              lost the contour below, so it supports what stands on it as a flat overhang.
// On a closed mesh no chain is dropped and the spans read as the ray raster's: the same layers
// solid on every pixel (tested).
//
// Cost: the slicing (layer_slices.h) plus O(loop edges × rows + pixels) per slice; memory one byte
// per pixel and slice. Slices run in parallel (OpenMP); the result does not depend on the thread
// count.
#pragma once

#include "core/support_model/support_raster.h"

namespace slim {

void rasterize_slices(const Surface& surface, const FaceAdjacency& adjacency, const OverhangRule& rule, SupportRaster& raster);

}  // namespace slim
