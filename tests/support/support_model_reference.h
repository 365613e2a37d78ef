// Brute-force references for the support model (core/support_model/support_raster.h, core/support_model/support_sweep.h),
// for small inputs: every ray against every face, every pixel and layer as a plain 3D array.
#pragma once

#include <vector>

#include "core/support_model/support_raster.h"
#include "core/support_model/support_sweep.h"

namespace slim::test {

// The solid spans of one pixel's vertical ray through its centre: every face intersected directly
// (barycentric test), sorted, nonzero winding. Exact unless the ray passes through an edge or a
// vertex (choose inputs that avoid it).
std::vector<SolidSpan> reference_spans(const Surface& s, const PixelGrid& g, int pixel);

// Whether the pixel's closed square overlaps the triangle's projection (Sutherland-Hodgman
// clipping of the triangle to the square leaves a polygon).
bool reference_overlaps(const PixelGrid& g, int pixel, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c);

// The grid sweep's rules (support_sweep.h) evaluated pixel by pixel and layer by layer, without
// events or counters: what GridSupportSweep::run must return.
GridSweepResult reference_sweep(const SupportRaster& raster, const SlicerLayers& layers, const GridSweepSettings& settings,
                                int offset_x, int offset_y);

}  // namespace slim::test
