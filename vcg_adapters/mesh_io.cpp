#include "vcg_adapters/mesh_io.h"

#include <stdexcept>

#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/clean.h>
#include <wrap/io_trimesh/export.h>
#include <wrap/io_trimesh/import.h>

#include "vcg_adapters/surface_adapter.h"

namespace slim::vcgx {
namespace {

class IoVertex;
class IoFace;
struct IoTypes : vcg::UsedTypes<vcg::Use<IoVertex>::AsVertexType, vcg::Use<IoFace>::AsFaceType> {};
class IoVertex : public vcg::Vertex<IoTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::Qualityd,
                                    vcg::vertex::Color4b, vcg::vertex::BitFlags> {};
class IoFace : public vcg::Face<IoTypes, vcg::face::VertexRef, vcg::face::Normal3d, vcg::face::Qualityd,
                                vcg::face::Color4b, vcg::face::BitFlags> {};
class IoMesh : public vcg::tri::TriMesh<std::vector<IoVertex>, std::vector<IoFace>> {};

}  // namespace

Surface load_surface(const std::string& path, FaceExtras* extras) {
  IoMesh m;
  int mask = 0;
  const int err = vcg::tri::io::Importer<IoMesh>::Open(m, path.c_str(), mask);
  if (err != 0 && vcg::tri::io::Importer<IoMesh>::ErrorCritical(err))
    throw std::runtime_error("cannot read " + path + ": " + vcg::tri::io::Importer<IoMesh>::ErrorMsg(err));
  // STL stores each triangle's corners separately; weld them so the surface is connected.
  vcg::tri::Clean<IoMesh>::RemoveDuplicateVertex(m);
  vcg::tri::Allocator<IoMesh>::CompactEveryVector(m);
  if (extras) {
    *extras = FaceExtras{};
    if (mask & vcg::tri::io::Mask::IOM_FACEQUALITY) {
      extras->quality.resize(m.fn);
      for (int i = 0; i < m.fn; ++i) extras->quality(i) = m.face[static_cast<size_t>(i)].Q();
    }
    if (mask & vcg::tri::io::Mask::IOM_FACEFLAGS) extras->selected = selected_faces(m);
  }
  return to_surface(m);
}

void save_surface(const std::string& path, const Surface& s, const FaceExtras& extras) {
  check_surface(s);
  IoMesh m;
  auto vi = vcg::tri::Allocator<IoMesh>::AddVertices(m, static_cast<size_t>(s.V.rows()));
  for (Eigen::Index i = 0; i < s.V.rows(); ++i, ++vi) vi->P() = vcg::Point3d(s.V(i, 0), s.V(i, 1), s.V(i, 2));
  auto fi = vcg::tri::Allocator<IoMesh>::AddFaces(m, static_cast<size_t>(s.F.rows()));
  for (Eigen::Index i = 0; i < s.F.rows(); ++i, ++fi)
    for (int k = 0; k < 3; ++k) fi->V(k) = &m.vert[static_cast<size_t>(s.F(i, k))];
  vcg::tri::UpdateNormal<IoMesh>::PerFaceNormalized(m);

  int mask = 0;
  if (extras.quality.size() > 0) {
    write_face_results(m, extras.quality, /*colourise=*/true, extras.selected.empty() ? nullptr : &extras.selected);
    mask |= vcg::tri::io::Mask::IOM_FACEQUALITY | vcg::tri::io::Mask::IOM_FACECOLOR;
  } else if (!extras.selected.empty()) {
    write_face_results(m, Eigen::VectorXd::Zero(s.F.rows()), false, &extras.selected);
  }
  if (!extras.selected.empty()) mask |= vcg::tri::io::Mask::IOM_FACEFLAGS;
  const int err = vcg::tri::io::Exporter<IoMesh>::Save(m, path.c_str(), mask);
  if (err != 0) throw std::runtime_error("cannot write " + path + ": " + vcg::tri::io::Exporter<IoMesh>::ErrorMsg(err));
}

}  // namespace slim::vcgx
