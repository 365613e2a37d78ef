// The print every stage reads: which way the part grows, the steepest overhang that prints without
// support, and which faces the build plate carries. The CLI, the filters and PyMeshLab fill one
// PrintSetup; the optimizer, the overhang analysis, the support model and the orientation search
// read it, and print_rule() resolves it for one part in the one place that does so.
//
//   PrintSetup setup;                          // +Z, 45 degrees, the automatic plate rule
//   setup.plate = PlateRule::within(0.05);     // or PlateRule::none()
//   PrintRule rule = print_rule(setup, bbox_diagonal(s.V));
//
// In: direction, any non-zero finite vector (it is normalised); alpha_max_deg, the self-supporting
// angle from the vertical in [0, 90) degrees (the slicer's threshold is 90 - alpha_max from the
// horizontal); plate, how far above the lowest point a face may lie and still rest on the plate.
// Out (PrintRule): the unit direction d, tau = sin(alpha_max) (a face is risky when n·d + tau < 0,
// overhang.h), and the plate tolerance in mm or none. Lengths are mm, as every mesh here.
#pragma once

#include <optional>

#include <Eigen/Core>

namespace slim {

// Which faces rest on the build plate: those whose three vertices lie within a tolerance of the
// lowest point along the print direction. Automatic: 1e-3 of the part's bounding-box diagonal,
// which absorbs the rounding of a flat base written in float without reaching a real step.
class PlateRule {
 public:
  static PlateRule automatic() { return PlateRule(Kind::Automatic, 0.0); }
  static PlateRule within(double tolerance_mm) { return PlateRule(Kind::Within, tolerance_mm); }
  static PlateRule none() { return PlateRule(Kind::None, 0.0); }
  // The tolerance in mm for a part whose bounding-box diagonal is diagonal_mm; nullopt: no face
  // rests on the plate. Throws std::invalid_argument for a tolerance that is negative or not
  // finite.
  std::optional<double> tolerance_mm(double diagonal_mm) const;
  bool is_automatic() const { return kind_ == Kind::Automatic; }

 private:
  enum class Kind { Automatic, Within, None };
  PlateRule(Kind kind, double tolerance_mm) : kind_(kind), tolerance_mm_(tolerance_mm) {}
  Kind kind_;
  double tolerance_mm_;
};

struct PrintSetup {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // the print direction, any non-zero vector
  double alpha_max_deg = 45.0;                           // self-supporting angle, [0, 90)
  PlateRule plate = PlateRule::automatic();
};

// A PrintSetup resolved for one part.
struct PrintRule {
  Eigen::Vector3d d = Eigen::Vector3d::UnitZ();  // unit print direction
  double alpha_max_deg = 45.0;
  double tau = 0.0;                              // sin(alpha_max)
  std::optional<double> plate_tolerance_mm;      // nullopt: no plate rule
};

// Resolves `setup` for a part whose bounding-box diagonal is diagonal_mm (read only by the
// automatic plate rule). Throws std::invalid_argument, in words a user can act on, for a zero or
// non-finite direction, an angle outside [0, 90) or a bad plate tolerance.
PrintRule print_rule(const PrintSetup& setup, double diagonal_mm);

// tau = sin(alpha_max); throws std::invalid_argument unless 0 <= alpha_max_deg < 90.
double self_supporting_tau(double alpha_max_deg);

// Returns the unit print direction; throws std::invalid_argument for a zero or non-finite vector.
Eigen::Vector3d unit_print_direction(const Eigen::Vector3d& d);

}  // namespace slim
