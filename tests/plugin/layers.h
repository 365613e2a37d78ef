// Test meshes as MeshLab layers. The calls used exist in every supported MeshLab API, so both
// plugin harnesses (tests/plugin for 2020.09, tests/plugin_2022) compile this against their own
// MeshLab headers; the including file brings MeshDocument in.
#pragma once

#include <QString>

#include "core/geometry/surface.h"

class MeshDocument;
class MeshModel;

namespace slim::test {

// Adds a new, current layer holding the surface (float positions, as MeshLab keeps them), with
// its bounding box and face normals up to date as after MeshLab's own import.
MeshModel* add_layer(MeshDocument& md, const Surface& s, const QString& label);

}  // namespace slim::test
