// Is the mesh at print size in millimetres? Every figure here (the support model's layers and
// grid, the plate tolerance, the budget in mm) takes the mesh as millimetres at the size it will
// print, and a file does not say its unit. A part whose largest bounding-box extent is under
// kSmallestPartMm or over kLargestPartMm is most likely in another unit: inches, centimetres
// and metres read too small, micrometres or a unit-less export too large.
//
//   std::optional<std::string> w = print_size_warning(V);   // V: #V by 3 positions
//
// Out: none for a part between the two sizes, else one sentence a user can act on (its size and
// the likely units, with the factor that turns them into millimetres); the caller adds how to
// scale it in its own interface. Reads the positions only; never throws.
#pragma once

#include <optional>
#include <string>

#include "core/geometry/surface.h"

namespace slim {

inline constexpr double kSmallestPartMm = 5.0;
inline constexpr double kLargestPartMm = 1000.0;

std::optional<std::string> print_size_warning(const Points& V);

}  // namespace slim
