// CMeshO (or any VCG triangle mesh) <-> slim::Surface, and the write-back of per-face results.
//
// Deleted vertices and faces are skipped. Surface vertex i is the i-th live vertex in container
// order and surface face j the j-th live face, so every write-back below walks the mesh in the
// same order and lines up with the arrays the core returned.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/update/color.h>
#include <vcg/complex/algorithms/update/selection.h>

#include "core/geometry/surface.h"
#include "vcg_adapters/quality_ramp.h"

namespace slim::vcg_adapters {

template <class MeshType>
Surface to_surface(const MeshType& m) {
  std::vector<int> live_index(m.vert.size(), -1);
  Surface s;
  s.V.resize(m.vn, 3);
  int nv = 0;
  for (size_t i = 0; i < m.vert.size(); ++i) {
    const auto& v = m.vert[i];
    if (v.IsD()) continue;
    live_index[i] = nv;
    s.V.row(nv++) << double(v.cP()[0]), double(v.cP()[1]), double(v.cP()[2]);
  }
  s.V.conservativeResize(nv, 3);
  s.F.resize(m.fn, 3);
  int nf = 0;
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    for (int k = 0; k < 3; ++k) {
      const auto slot = static_cast<size_t>(f.cV(k) - &m.vert[0]);
      if (slot >= live_index.size() || live_index[slot] < 0)
        throw std::invalid_argument("face " + std::to_string(nf) + " refers to a deleted or foreign vertex");
      s.F(nf, k) = live_index[slot];
    }
    ++nf;
  }
  s.F.conservativeResize(nf, 3);
  return s;
}

// Per live face: is it selected?
template <class MeshType>
std::vector<bool> selected_faces(const MeshType& m) {
  std::vector<bool> sel;
  sel.reserve(static_cast<size_t>(m.fn));
  for (const auto& f : m.face)
    if (!f.IsD()) sel.push_back(f.IsS());
  return sel;
}

// Moves the live vertices to V (#V by 3, the order of to_surface) and refreshes normals and bbox.
template <class MeshType>
void write_positions(MeshType& m, const Points& V) {
  if (V.rows() != m.vn) throw std::invalid_argument("write_positions: vertex count mismatch");
  Eigen::Index i = 0;
  using Scalar = typename MeshType::ScalarType;
  for (auto& v : m.vert) {
    if (v.IsD()) continue;
    v.P() = typename MeshType::CoordType(Scalar(V(i, 0)), Scalar(V(i, 1)), Scalar(V(i, 2)));
    ++i;
  }
  vcg::tri::UpdateNormal<MeshType>::PerFaceNormalized(m);
  vcg::tri::UpdateNormal<MeshType>::PerVertexNormalized(m);
  vcg::tri::UpdateBounding<MeshType>::Box(m);
}

// Writes per-face quality (#F values in to_surface order); optionally colours faces on the fixed
// ramp (quality_ramp.h) and replaces the face selection by `select` (true = selected).
template <class MeshType>
void write_face_results(MeshType& m, const Eigen::VectorXd& quality, bool colourise,
                        const std::vector<bool>* select) {
  if (quality.size() != m.fn) throw std::invalid_argument("write_face_results: face count mismatch");
  if (select && select->size() != static_cast<size_t>(m.fn))
    throw std::invalid_argument("write_face_results: selection size mismatch");
  Eigen::Index i = 0;
  for (auto& f : m.face) {
    if (f.IsD()) continue;
    f.Q() = typename MeshType::ScalarType(quality(i));
    if (colourise) f.C().SetColorRamp(float(kQualityRampMin), float(kQualityRampMax), float(quality(i)));
    if (select) {
      if ((*select)[static_cast<size_t>(i)]) f.SetS(); else f.ClearS();
    }
    ++i;
  }
}

// Writes per-vertex quality (#V values in to_surface order).
template <class MeshType>
void write_vertex_quality(MeshType& m, const Eigen::VectorXd& quality) {
  if (quality.size() != m.vn) throw std::invalid_argument("write_vertex_quality: vertex count mismatch");
  Eigen::Index i = 0;
  for (auto& v : m.vert)
    if (!v.IsD()) v.Q() = typename MeshType::ScalarType(quality(i++));
}

}  // namespace slim::vcg_adapters
