#include "core/print/print_size.h"

#include <cstdio>

namespace slim {

std::optional<std::string> print_size_warning(const Points& V) {
  if (V.rows() == 0) return std::nullopt;
  const double largest = (V.colwise().maxCoeff() - V.colwise().minCoeff()).maxCoeff();
  if (!(largest < kSmallestPartMm || largest > kLargestPartMm)) return std::nullopt;  // NaN: no warning
  char text[320];
  if (largest < kSmallestPartMm)
    std::snprintf(text, sizeof text,
                  "the part is %.3g mm across at its largest, under %g mm: the mesh is taken in millimetres at print "
                  "size, and this one is likely in inches (x 25.4), centimetres (x 10) or metres (x 1000)",
                  largest, kSmallestPartMm);
  else
    std::snprintf(text, sizeof text,
                  "the part is %.4g mm across at its largest, over %g mm: the mesh is taken in millimetres at print "
                  "size, and this one is likely a unit-less export or in micrometres (x 0.001)",
                  largest, kLargestPartMm);
  return std::string(text);
}

}  // namespace slim
