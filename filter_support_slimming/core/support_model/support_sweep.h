// PrusaSlicer's grid support, swept down layer by layer over a SupportRaster for one grid phase.
//
//   GridSupportSweep sweep(raster, layers, settings);   // the phase-independent events, once
//   GridSweepResult r = sweep.run(offset_x, offset_y);  // one phase: cells offset by that many pixels
//
// Inputs
//   raster    SupportRaster (support_raster.h) of the part in the print frame, plate at z = 0.
//   layers    SlicerLayers: the slicer's layer heights and how many layers the part spans.
//   settings  GridSweepSettings: cell size in pixels, the gaps, and the material per unit
//             (derived from the slicer's flows by support_model.cpp).
// Output (GridSweepResult, mm³ and mm²) for cells of settings.pixels_per_cell pixels whose
// boundaries lie offset_x, offset_y pixels (in [0, pixels_per_cell)) past the raster's origin.
//
// The rules, per support layer j from the top down (support layers coincide with the object's):
//   - an overhang at object layer k puts a contact in its pixel's cell at the highest support
//     layer whose top lies contact_distance below layer k's bottom (none below the first layer);
//     a feature over a pixel inside the part just below it (the pixel and its four neighbours
//     filled) is hidden and ignored, but one on the part's outline there counts: the slicer
//     rasterises its contacts with any coverage, so a sliver of one reaches the cell;
//   - a cell is a column at j when it has a contact at j (j >= 1: a contact in the first layer
//     alone builds nothing, PrusaSlicer takes it out of the first layer), or was one at j + 1 and the projection
//     passes: some pixel of it is free of the part in object layers j and j + 1, or lies on the
//     part's outline there (a neighbour free) with the outline in its own half. The slicer fills
//     its grid cells up to the part and keeps any sliver of a cell the part leaves free, so a
//     column whose cell the part's side all but covers goes on down, and fills the cell again where
//     the part recedes below; a cell the part covers beyond its outline stops it, and so does one
//     whose outline has moved past the midpoint into the neighbour (where the neighbour's span
//     starts above, or ends below, the pixel's: the outline runs between their centres);
//   - a column's area at j: its pixels free of the part in object layers j - g .. j + g (g the
//     layers within contact_distance), less xy_gap along the part's outline there;
//   - support layers: PrusaSlicer splits each gap between contact layers into equal layers of at
//     most max_support_layer_height; their thickness sets the flow per height and the depth of the
//     interface_layers dense layers;
//   - cells within that depth below a dense contact are interface, the rest base; the
//     base islands get a sheath along their outline (cell sides facing non-base cells, and the
//     part's outline inside them) and fill lines along x on the cell boundaries inside them
//     (PrusaSlicer anchors its support lines where the grid is, one cell apart), joined at
//     alternate ends into a zigzag by links that run along the island's outline, out along a row
//     past a line's end to where the row ends and back (half a link per end); pixels where a
//     column meets the part's top get a bottom interface;
//   - the first layer: the base columns' pixels grown by first_layer_expansion around, not
//     through, the part, less the interface columns' pixels, at its own density, with a sheath;
//     the interface columns there are dense layers like any other.
// Pixel outlines are staircases; their length is scaled by pi/4 (the mean ratio for outlines of
// every direction), except along cell sides, which are straight.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/support_model/support_raster.h"

namespace slim {

struct SlicerLayers {
  double first_height = 0.2;  // mm
  double height = 0.2;        // mm
  int count = 0;              // object layers
  double print_z(int k) const { return k <= 0 ? first_height : first_height + k * height; }
  double bottom_z(int k) const { return k <= 0 ? 0.0 : print_z(k - 1); }
  double slice_z(int k) const { return 0.5 * (bottom_z(k) + print_z(k)); }
  double thickness(int k) const { return k <= 0 ? first_height : height; }
  int first_slice_at_or_above(double z) const;  // smallest k with slice_z(k) >= z (may be count)
  int last_slice_at_or_below(double z) const;   // largest k with slice_z(k) <= z (may be -1)
};

struct GridSweepSettings {
  int pixels_per_cell = 4;
  double contact_distance = 0.2;          // mm, between support and overhang or landing
  double xy_gap = 0.225;                  // mm, between support and the part's side
  double grid_spacing = 2.857;            // mm, the cell (the support lines' spacing)
  double extrusion_width = 0.4;           // mm, support lines
  double nozzle_diameter = 0.4;           // mm, the bridging lines of a landing
  double max_support_layer_height = 0.3;  // mm, the support's own layers between contacts
  int interface_layers = 3;
  bool sheath = true;
  double first_layer_density = 0.9;
  double first_layer_expansion = 3.0;     // mm
};

// The material of one support layer of thickness t, per unit: lines of width w are
// t × (w - t(1 - pi/4)) in section (PrusaSlicer's rounded rectangle), so a mm of line per mm of
// height is line_per_mm2 mm³; the interfaces are lines one line spacing (at the object's layer
// height) apart (interface_per_mm3 per mm² and mm of height); a base fill line ends fill_end
// short of the cell boundary where its island ends.
struct SweepRates {
  double line_per_mm2 = 0.0, fill_end = 0.0, interface_per_mm3 = 0.0;
  double bottom_interface_per_mm2 = 0.0;  // a landing: bridging contact and dense layers, less the
                                          // fill they replace
  double interface_depth = 0.0;           // object layers of top interface under a dense contact
  double first_fill_per_mm2 = 0.0, first_sheath_per_mm = 0.0, first_inset = 0.0;  // layer 0
};
SweepRates sweep_rates(const GridSweepSettings& s, const SlicerLayers& layers, double thickness);

// PrusaSlicer's support layers: between consecutive contact layers (and from the first layer up to
// the lowest) the gap is split into equal layers no thicker than max_height. Returns, per object
// layer j, the thickness of the support layer printed there (the first layer's for j = 0, the
// object's layer height above the highest contact). has_contact: per object layer, whether any
// contact lies there.
std::vector<double> support_layer_thickness(const std::vector<char>& has_contact, const SlicerLayers& layers, double max_height);

struct GridSweepResult {
  double base_fill = 0.0, sheath = 0.0, top_interface = 0.0, bottom_interface = 0.0, first_layer = 0.0;
  double contact_area = 0.0, landing_area = 0.0, column_volume = 0.0;
  std::vector<double> layer;  // per support layer: all its material (landings at the layer below)
  double total() const { return base_fill + sheath + top_interface + bottom_interface + first_layer; }
};

class GridSupportSweep {
 public:
  GridSupportSweep(const SupportRaster& raster, const SlicerLayers& layers, const GridSweepSettings& settings);
  GridSweepResult run(int offset_x, int offset_y) const;

  enum Kind : std::uint8_t { kTrim, kBlock, kTop, kContact, kDense, kOutline, kKinds };
  struct Event {
    int pixel;
    Kind kind;
    std::int8_t delta;
  };
  struct RawEvent {  // an event and the layer it happens at
    int layer;
    Event event;
  };

 private:
  void pixel_events(const SupportRaster& raster, std::vector<RawEvent>& raw, std::vector<int>& trim_begin,
                    std::vector<std::pair<int, int>>& trims, std::vector<char>& has_contact);
  struct PixelRanges {  // per pixel, sorted layer ranges [first, second]: offsets and the ranges
    const std::vector<int>& offset;
    const std::vector<std::pair<int, int>>& ranges;
    bool empty(int p) const { return offset[p] == offset[p + 1]; }
    const std::pair<int, int>* begin(int p) const { return ranges.data() + offset[p]; }
    const std::pair<int, int>* end(int p) const { return ranges.data() + offset[p + 1]; }
  };
  void block_events(const PixelRanges& solid, std::vector<RawEvent>& raw) const;
  void outline_events(const std::vector<int>& trim_begin, const std::vector<std::pair<int, int>>& trims,
                      std::vector<RawEvent>& raw) const;
  double first_layer(const std::vector<int>& columns, const std::vector<int>& interface_cells, int cells_x, int offset_x,
                     int offset_y) const;

  PixelGrid grid_;
  SlicerLayers layers_;
  GridSweepSettings settings_;
  std::vector<int> event_begin_;  // layers + 1 offsets into events_, layer count - 1 first
  std::vector<Event> events_;
  std::vector<std::uint8_t> solid_first_;    // per pixel: the part fills it in the first layer
  std::vector<std::uint8_t> trimmed_first_;  // per pixel: the part is within reach of layer 0
  std::vector<SweepRates> rates_;            // per object layer
  int top_layer_ = -1;                       // highest layer with any event
};

}  // namespace slim
