// MeshLab 2022.02's names for what filters.cpp uses, and the calls that changed since 2020.09
// (api_2020_09/meshlab_api.h has the same declarations for that API). Later releases (2025.07)
// keep the FilterPlugin API but split common/parameters/ into rich_parameter/*.h and value/*.h
// and renamed three classes; the names below are the same for all of them.
#pragma once

#include <common/GLLogStream.h>
#include <common/ml_document/mesh_document.h>
#include <common/parameters/rich_parameter_list.h>

// The split headers of later releases (rich_parameter_list.h includes them all).
#if __has_include(<common/parameters/rich_parameter/rich_percentage.h>)
#define SLIM_MESHLAB_SPLIT_PARAMETERS 1
#endif

namespace slim::meshlab_api {

using RichDirection = ::RichDirection;
#ifdef SLIM_MESHLAB_SPLIT_PARAMETERS
using RichAbsPerc = ::RichPercentage;  // still "RichAbsPerc" in scripts (stringType)
using Point3Value = ::Point3Value;
inline bool is_point3(const Value& v) { return v.isPoint3(); }
#else
using RichAbsPerc = ::RichAbsPerc;
using Point3Value = ::Point3fValue;
inline bool is_point3(const Value& v) { return v.isPoint3f(); }
#endif

// The index an enum parameter holds (2022.02 keeps it in an IntValue).
inline int enum_index(const RichParameter& p) { return p.value().getInt(); }

// Scripts written for 2020.09 (ours in examples/ too) hold 3D points as RichPoint3f, which
// 2022.02 reads back as a RichPosition: accept it where a RichDirection is asked for.
inline bool same_parameter_type(const RichParameter& a, const RichParameter& b) {
  return a.stringType() == b.stringType() || (is_point3(a.value()) && is_point3(b.value()));
}

inline void delete_layer(MeshDocument& md, MeshModel* layer) { md.delMesh(layer->id()); }

}  // namespace slim::meshlab_api
