// The support a slicer builds under a part: an estimate of the extruded support material.
//
//   SupportEstimate estimate_support(surface, options)
//
// Inputs
//   surface  #V by 3 positions (mm), #F by 3 outward-oriented faces that share their vertices (a
//            welded mesh: the lowest-point and bottom-crease rules below read the faces around a
//            vertex and an edge). Any pose: the print direction of the options says which way is
//            up, and the part is dropped onto the plate first, as slicers do.
//   options  SupportModelOptions below: print direction, alpha_max, the slicer's settings. The
//            defaults are PrusaSlicer 2.5's, with the settings of tools/evaluate.sh (0.2 mm layers,
//            a 0.4 mm nozzle, automatic supports at threshold 90 - alpha_max).
// Output (SupportEstimate)
//   volume_mm3  the support filament the slicer extrudes (mm³ of plastic: what its G-code's
//               "Support material" and "Support material interface" sections add up to),
//               averaged over grid phases; its parts (base fill, sheath, interfaces, first
//               layer), the spread over phases, and the footprint.
//
// How it models the slicer (PrusaSlicer's "grid" support style, read from its sources):
//   - Overhangs, layer by layer: a point of the surface needs support when the part at its layer
//     reaches beyond the layer below by more than layer_height / tan(threshold + 1°) (the slicer's
//     threshold is inclusive): faces less steep than that, bottom creases (an edge with the solid
//     above it on both sides, such as a keel's ridge) that slope less, and lowest points (a vertex
//     below all its neighbours). Each such feature marks the grid cells it touches, at the layer
//     the slicer puts its contact: contact_distance below it; nothing lower than the first layer.
//   - The grid: the plate is divided into square cells of grid_spacing (the support lines'
//     spacing), aligned to the part's bounding-box centre. A cell any overhang touches becomes a
//     support column: the whole cell, minus the part and an xy_gap around it. The column goes down
//     layer by layer while some of the cell stays free of the part, so it stands on the plate or
//     on the part below (a shadowed overhang stands on the model), and flows around what only
//     covers part of the cell. Tiny islands are therefore never dropped: each is stretched to a
//     full cell, which is how the grid style treats them.
//   - Material per layer: the fill (lines one grid cell apart) over the columns' area, a sheath
//     loop around every island (its outline against empty cells and around the part), dense
//     interface layers under overhangs flatter than dense_interface_slope_deg (PrusaSlicer prints
//     none under steeper ones) and on the part where a column lands on it, and a first layer
//     expanded by first_layer_expansion at first_layer_density.
//   - Not modelled: PrusaSlicer's "don't support bridges" (it leaves out the middle of flat
//     bottoms anchored at their sides; organic parts have almost none), the exact fill-line count
//     of each island (the phase average smooths it), support enforcers and blockers.
//
// Resolution: a ray raster along the print direction with pixels of grid_spacing /
// pixels_per_cell (0.71 mm by default): the part's solid along each pixel's vertical ray (exact at
// the pixel centre), the overhangs conservatively (every pixel they touch). The sweep works on the
// slicer's own layers (layer_height) and cells.
//
// Grid phase. The slicer's grid is aligned to the part's bounding box, so its figure jumps by
// several % when the part moves by a fraction of a cell; an optimizer must not win by shifting the
// part against the grid. The estimate is the mean over grid_phases cell offsets spread over the
// cell (1: the slicer's own phase only; pixels_per_cell: offsets k/n of a cell in x and a
// permutation of them in y; pixels_per_cell²: every pixel offset), so moving the part changes it
// only as much as a different sample of the same average. Turning about the print axis changes
// the grid's angle to the part and the direction of the support lines (along x), which phases do
// not cover; turns > 1 also averages over turns spread over half a turn (2: 0° and 90°, as the
// judge's quarter turns; 4: every 45°).
//
// Determinism: the phases run in parallel (OpenMP), each in a fixed order, and are summed in
// phase order: the result does not depend on the thread count.
//
// Cost (bench/support_model_bench.cpp, this machine): see docs/support-model.md. It is linear in
// the faces (the raster) plus cells × layers × phases (the sweep).
//
// Errors: std::invalid_argument with a readable reason for a surface with no faces, bad indices,
// non-finite coordinates, zero height, or options out of range.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/surface.h"

namespace slim {

struct SupportModelOptions {
  // The print.
  Eigen::Vector3d print_direction = Eigen::Vector3d::UnitZ();  // any non-zero vector; normalised
  double alpha_max_deg = 45.0;        // self-supporting angle from the vertical, (0, 90): the
                                      // slicer's threshold is 90 - alpha_max from the horizontal
  double threshold_slack_deg = 1.0;   // PrusaSlicer adds 1° to its threshold (inclusive rule)
  // The slicer (PrusaSlicer 2.5 defaults; layer and nozzle as tools/evaluate.sh slices).
  double layer_height = 0.2;          // mm
  double first_layer_height = 0.2;    // mm
  double nozzle_diameter = 0.4;       // mm
  double extrusion_width = 0.4;       // mm, support lines (PrusaSlicer: the nozzle diameter)
  double max_support_layer_height = 0.3;  // mm: PrusaSlicer splits the gaps between contacts
                                      // into support layers up to 0.75 × nozzle thick; their
                                      // thickness sets the flow per height and interface depth
  double grid_spacing = 2.857;        // mm, support line spacing 2.5 + line spacing 0.357: the
                                      // grid cell
  double contact_distance = 0.2;      // mm, gap between support and overhang (and landing)
  double xy_gap = 0.225;              // mm, gap to the part (50% of the 0.45 mm outer perimeter)
  int interface_layers = 3;           // dense layers under overhangs and on landings
  double dense_interface_overhang = 0.27;  // mm: dense interface only where a layer reaches
                                      // farther than this beyond the one below (60% of the
                                      // outer perimeter width)
  double first_layer_density = 0.9;   // share of the first layer that is filled
  double first_layer_expansion = 3.0; // mm, the first layer's support grows this much outward
  bool sheath = true;                 // a loop around every island of the base layers
  bool bottom_creases = true;         // keel ridges and other bottom creases need support
  bool lowest_points = true;          // a vertex below all its neighbours needs support
  // The model.
  int pixels_per_cell = 4;            // raster pixels along a grid cell, >= 1
  int grid_phases = 4;                // 1, pixels_per_cell or pixels_per_cell²
  int turns = 1;                      // turns about the print axis averaged, spread over 180°
  int threads = 0;                    // OpenMP threads; 0: the runtime's default
};

struct SupportEstimate {
  double volume_mm3 = 0.0;            // all support filament: the sum of the five parts below
  double base_fill_mm3 = 0.0;         // the sparse lines inside the columns (above the first layer)
  double sheath_mm3 = 0.0;            // the loops around the islands (above the first layer)
  double top_interface_mm3 = 0.0;     // dense layers under overhangs
  double bottom_interface_mm3 = 0.0;  // dense layers where columns land on the part
  double first_layer_mm3 = 0.0;       // the first layer, expanded and dense
  double min_phase_mm3 = 0.0;         // the smallest and largest phase's volume: the jitter the
  double max_phase_mm3 = 0.0;         // average removes
  std::vector<double> phase_mm3;      // every phase's (and turn's) volume, in order
  double contact_area_mm2 = 0.0;      // area of the cells with an overhang contact, summed over
                                      // layers (phase mean): the footprint
  double landing_area_mm2 = 0.0;      // area where columns land on the part (phase mean)
  double column_volume_mm3 = 0.0;     // volume of the columns' space (area × height, phase mean)
  std::vector<double> layer_mm3;      // per slicer layer from the plate up (layer_height apart,
                                      // the first first_layer_height): its share (phase mean)
  double pixel_mm = 0.0;              // raster pixel used
  int layers = 0;                     // slicer layers swept
  int cells = 0;                      // grid cells in x times y
};

SupportEstimate estimate_support(const Surface& surface, const SupportModelOptions& options = {});

}  // namespace slim
