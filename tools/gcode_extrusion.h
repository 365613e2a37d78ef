// Filament extruded per feature type in a sliced G-code file: the judge's measure of support.
//
// In:  G-code text as PrusaSlicer writes it with --gcode-comments: ";TYPE:<name>" lines open a
//      section of one feature type (e.g. "Support material", "Support material interface"),
//      ";WIPE_START"/";WIPE_END" bracket wipe moves, and a footer of "; key = value" comments
//      carries the slicer's own totals ("filament used [mm]") and every setting.
// Out: millimetres of filament extruded in each section type, their total, and the footer.
//
// What counts as extruded: a G0/G1/G2/G3 move whose E goes up while X or Y moves, outside a wipe.
// Retractions and unretractions (E alone, or E with only Z) and wipes (E going down while the
// nozzle moves) put no plastic on the part, and the slicer's "filament used" leaves them out too.
// E is tracked through M82/M83 (absolute/relative E), G90/G91 (which also switch E) and G92
// (which resets the logical position of the axes it names, or of all axes when it names none).
#pragma once

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
  // Filament in the "Support material" and "Support material interface" sections.
  double support_mm() const;
  double type_mm(const std::string& type) const;
};

// Parses a whole G-code stream. Throws std::runtime_error("line N: ...") on a malformed number
// after an axis letter that matters (X, Y, Z, E).
GcodeExtrusion measure_extrusion(std::istream& gcode);

// Cross-section area of a filament of the given diameter (mm²): filament mm × this = mm³.
double filament_area(double diameter_mm);

}  // namespace slim::eval
