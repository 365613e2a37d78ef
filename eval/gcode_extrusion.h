// Filament extruded per feature type in a sliced G-code file: the judge's measure of support.
//
// In:  G-code text as PrusaSlicer writes it with --gcode-comments, or as CuraEngine writes it:
//      ";TYPE:<name>" lines open a section of one feature type (PrusaSlicer: "Support material",
//      "Support material interface"; Cura: "SUPPORT", "SUPPORT-INTERFACE"), PrusaSlicer's
//      ";WIPE_START"/";WIPE_END" bracket wipe moves, and its footer of "; key = value" comments
//      carries the slicer's own totals ("filament used [mm]") and every setting (Cura's command
//      line writes neither: its header's ";Filament used:" stays 0 without its front end).
// Out: millimetres of filament extruded in each section type, their total, and the footer.
//
// What counts as extruded: a G0/G1/G2/G3 move whose E goes up while X or Y moves, outside a wipe.
// Retractions and unretractions (E alone, or E with only Z) and wipes (E going down while the
// nozzle moves) put no plastic on the part, and the slicer's "filament used" leaves them out too.
// E is tracked through M82/M83 (absolute/relative E), G90/G91 (which also switch E) and G92
// (which resets the logical position of the axes it names, or of all axes when it names none).
#pragma once

#include <functional>
#include <istream>
#include <map>
#include <optional>
#include <string>

namespace slim::eval {

struct GcodeExtrusion {
  std::map<std::string, double> by_type;  // mm of filament per ";TYPE:" name; "" before the first
  double total_mm = 0.0;                  // sum over all types
  // Every "; key = value" comment line: the footer's settings and totals (a later line wins).
  std::map<std::string, std::string> settings;

  // The footer's "filament used [mm]" (the slicer's own total, summed over extruders), if present.
  std::optional<double> slicer_total_mm() const;
  // The "filament_diameter" setting (the first extruder's), if present.
  std::optional<double> filament_diameter() const;
  // Filament in the support sections of either slicer: "Support material" and "Support
  // material interface" (PrusaSlicer), "SUPPORT" and "SUPPORT-INTERFACE" (Cura).
  double support_mm() const;
  // Of that, the interface sections alone (the dense layers under and over the part).
  double support_interface_mm() const;
  double type_mm(const std::string& type) const;
};

// Whether a ";TYPE:" name is a support section of either slicer.
bool is_support_type(const std::string& type);

// One extruding move, for drawing the tool path: its section type, its start and end (mm, the
// slicer's bed coordinates) and the filament it used (mm).
struct ExtrusionMove {
  const std::string& type;
  double from[3], to[3];
  double filament_mm;
};
using ExtrusionVisitor = std::function<void(const ExtrusionMove&)>;

// Parses a whole G-code stream; calls `visit` (when given) for every move that counts as
// extruded. Throws std::runtime_error("line N: ...") on a malformed number after an axis letter
// that matters (X, Y, Z, E).
GcodeExtrusion measure_extrusion(std::istream& gcode, const ExtrusionVisitor& visit = {});

// Cross-section area of a filament of the given diameter (mm²): filament mm × this = mm³.
double filament_area(double diameter_mm);

}  // namespace slim::eval
