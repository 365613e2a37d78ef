// Synthetic creatures: a blobby body on legs, a neck and a head, as the zero level set of a
// smooth union of ellipsoids and capsules, meshed by VCG's marching cubes. They have what scans
// of figurines have and the closed-form shapes (a T, a mushroom) lack: rounded bellies, chins
// and thighs that overhang gradually, blended into the rest.
//
// Every creature is closed and outward-oriented, +Z up, standing on its feet on z = 0 (the feet
// are cut flat by the plate), in mm: about 60 mm long or tall. `cell` is the marching-cubes grid
// spacing in mm (the mesh has roughly 2.5 (size / cell)^2 faces). Needs VCG (tests built with it).
#pragma once

#include <string>
#include <vector>

#include "core/geometry/surface.h"

namespace slim::test {

// quadruped: a dog-like body on four legs, a neck rising forward and a head with a snout.
// long_neck: a heavy, low-bellied body on four thick legs, a long neck and a long tail.
// upright:   a penguin-like upright body on two short legs, a round head and a pointed beak.
std::vector<std::string> creature_names();

// Throws std::invalid_argument for an unknown name or a cell outside [0.2, 5] mm.
Surface creature(const std::string& name, double cell = 0.8);

}  // namespace slim::test
