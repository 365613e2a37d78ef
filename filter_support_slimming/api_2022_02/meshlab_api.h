// MeshLab 2022.02's names for what filters.cpp uses, and the calls that changed since 2020.09
// (api_2020_09/meshlab_api.h has the same declarations for that API).
#pragma once

#include <common/GLLogStream.h>
#include <common/ml_document/mesh_document.h>
#include <common/parameters/rich_parameter_list.h>

namespace slim::meshlab_api {

using RichDirection = ::RichDirection;

// The index an enum parameter holds (2022.02 keeps it in an IntValue).
inline int enum_index(const RichParameter& p) { return p.value().getInt(); }

// Scripts written for 2020.09 (ours in examples/ too) hold 3D points as RichPoint3f, which
// 2022.02 reads back as a RichPosition: accept it where a RichDirection is asked for.
inline bool same_parameter_type(const RichParameter& a, const RichParameter& b) {
  return a.stringType() == b.stringType() || (a.value().isPoint3f() && b.value().isPoint3f());
}

inline void delete_layer(MeshDocument& md, MeshModel* layer) { md.delMesh(layer->id()); }

}  // namespace slim::meshlab_api
