// Risky ("overhanging") faces, paper §I-A.
//
// A face with unit normal n is risky when  n·d + tau < 0,  tau = sin(alpha_max),
// where d is the print (build) direction and alpha_max the self-supporting angle measured from
// the vertical: alpha_max = 45° is the usual slicer rule; at alpha_max = 0 every face that points
// below the horizontal is risky.
//
// Faces resting on the build plate are carried by it and are never risky: all three vertices lie
// within the plate tolerance (mm, PrintSetup's plate rule) of the lowest point of the mesh along d.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/checked_surface.h"
#include "core/geometry/surface.h"
#include "core/print/print_setup.h"

namespace slim {

struct OverhangReport {
  Eigen::VectorXd quality;     // #F: n·d + tau (< 0 means risky); plate faces get +1
  std::vector<bool> risky;     // #F
  std::vector<bool> on_plate;  // #F: resting on the build plate (never risky)
  Eigen::Index risky_count = 0;
  Eigen::Index plate_count = 0;
  double risky_area = 0.0;     // mm²
  // sum over risky faces of area * -(n·d + tau) (mm²): how far the overhangs are from safe. It
  // falls smoothly while faces tilt towards the threshold, when the risky area does not move yet.
  double risky_deficit = 0.0;
  // sum over risky faces of area * -(n·d) * (height of the face's centroid above the plate)
  // (mm³): the volume of the prism between each overhang and the plate, a support-volume
  // estimate. Ranks meshes by slicer support volume far better than the risky area does (an
  // overhang just above the plate needs little support, one high up needs a tall column).
  double shadow_volume = 0.0;
  double total_area = 0.0;     // mm²
  double plate_height = 0.0;   // min over vertices of v·d (mm)
  double risky_share() const { return total_area > 0.0 ? risky_area / total_area : 0.0; }
};

// The rule for one face, the one place it is written (analyse_overhang and the orientation
// search's exact score both apply it):
//   h0, h1, h2  its vertices' heights along d (mm);  plate  the lowest vertex's height (mm);
//   tolerance   the plate tolerance (mm; none: no face rests on the plate);
//   quality     n·d + tau, its unit normal n, tau = sin(alpha_max).
// Plate: all three vertices within tolerance of the plate. Risky: not on the plate, and
// quality < 0.
enum class FaceSupport { Plate, Safe, Risky };
inline FaceSupport face_support(double h0, double h1, double h2, double plate, const std::optional<double>& tolerance,
                                double quality) {
  if (tolerance && h0 - plate <= *tolerance && h1 - plate <= *tolerance && h2 - plate <= *tolerance)
    return FaceSupport::Plate;
  return quality < 0.0 ? FaceSupport::Risky : FaceSupport::Safe;
}

// A risky face's share of the shadow volume: area (mm²) x its footprint -(n·d) x the height of its
// centroid above the plate (mm), in mm³.
inline double face_shadow(double area, double n_dot_d, double centroid_above_plate) {
  return area * (n_dot_d < 0.0 ? -n_dot_d : 0.0) * centroid_above_plate;
}

// Classifies every face. Throws std::invalid_argument (readable message) for a surface with no
// faces, bad indices, non-finite coordinates, or bad options.
// The automatic plate rule reads the surface's own bounding box.
OverhangReport analyse_overhang(const Surface& s, const PrintSetup& print = {});
// The same for a surface already checked and a rule already resolved (the optimizer measures
// every iterate this way, with the input's rule).
OverhangReport analyse_overhang(const CheckedSurface& s, const PrintRule& rule);

}  // namespace slim
