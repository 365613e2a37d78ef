// MeshLab 2020.09's names for what filters.cpp uses, and the calls that changed in 2022.02
// (api_2022_02/meshlab_api.h has the same declarations for that API).
#pragma once

#include <common/interfaces.h>
#include <common/meshmodel.h>

namespace slim::meshlab_api {

// A 3D direction in a filter's dialog (2022.02 has a dedicated RichDirection).
using RichDirection = ::RichPoint3f;
using RichAbsPerc = ::RichAbsPerc;

// The index an enum parameter holds (2020.09 keeps it in an EnumValue).
inline int enum_index(const RichParameter& p) { return p.value().getEnum(); }

// Whether a host's parameter can stand for ours: the same type.
inline bool same_parameter_type(const RichParameter& a, const RichParameter& b) { return a.stringType() == b.stringType(); }

inline void delete_layer(MeshDocument& md, MeshModel* layer) { md.delMesh(layer); }

}  // namespace slim::meshlab_api
