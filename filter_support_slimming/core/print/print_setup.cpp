#include "core/print/print_setup.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace slim {

std::optional<double> PlateRule::tolerance_mm(double diagonal_mm) const {
  switch (kind_) {
    case Kind::Automatic:
      return 1e-3 * diagonal_mm;
    case Kind::Within:
      if (!std::isfinite(tolerance_mm_)) throw std::invalid_argument("the build plate tolerance must be finite");
      if (tolerance_mm_ < 0.0)
        throw std::invalid_argument("the build plate tolerance must be >= 0 mm, got " + std::to_string(tolerance_mm_));
      return tolerance_mm_;
    case Kind::None:
      break;
  }
  return std::nullopt;
}

double self_supporting_tau(double alpha_max_deg) {
  if (!(alpha_max_deg >= 0.0 && alpha_max_deg < 90.0))
    throw std::invalid_argument("the self-supporting angle must be in [0, 90) degrees, got " +
                                std::to_string(alpha_max_deg));
  return std::sin(alpha_max_deg * M_PI / 180.0);
}

Eigen::Vector3d unit_print_direction(const Eigen::Vector3d& d) {
  const double len = d.norm();
  if (!std::isfinite(len) || len < 1e-12)
    throw std::invalid_argument("the print direction must be a non-zero vector");
  return d / len;
}

PrintRule print_rule(const PrintSetup& setup, double diagonal_mm) {
  PrintRule rule;
  rule.d = unit_print_direction(setup.direction);
  rule.alpha_max_deg = setup.alpha_max_deg;
  rule.tau = self_supporting_tau(setup.alpha_max_deg);
  rule.plate_tolerance_mm = setup.plate.tolerance_mm(diagonal_mm);
  return rule;
}

}  // namespace slim
