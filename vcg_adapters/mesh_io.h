// Mesh files <-> slim::Surface through VCG's importers and exporters (PLY, STL, OBJ, OFF), for
// the CLI and the tests; OBJ and STL are read here instead (VCG 2020.09 drops OBJ faces and
// over-reads binary STL headers). The plugin does not use this: MeshLab does its own IO.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/surface.h"

namespace slim::vcgx {

// Per-face extras written with (or read back from) a surface. Empty means absent.
struct FaceExtras {
  Eigen::VectorXd quality;       // #F, written as face quality (PLY only) and as the ramp colour
  std::vector<bool> selected;    // #F, written as a per-face flag (PLY only)
};

// Reads a mesh; throws std::runtime_error("cannot read <path>: <VCG's reason>") on failure.
// Duplicate vertices written by STL are merged so the surface is connected. When `extras` is
// given, it receives the face quality and selection the file carries (left empty otherwise).
Surface load_surface(const std::string& path, FaceExtras* extras = nullptr);

// Writes a surface; the format follows the extension. Throws std::runtime_error on failure.
void save_surface(const std::string& path, const Surface& s, const FaceExtras& extras = {});

}  // namespace slim::vcgx
