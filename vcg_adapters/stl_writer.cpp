#include "vcg_adapters/stl_writer.h"

#include <stdexcept>
#include <vector>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/export.h>

#include "vcg_adapters/surface_adapter.h"

namespace slim::vcg_adapters {

namespace {

// The VCG mesh the exporter reads: positions in double, face normals, quality and colour.
class IoVertex;
class IoFace;
struct IoTypes : vcg::UsedTypes<vcg::Use<IoVertex>::AsVertexType, vcg::Use<IoFace>::AsFaceType> {};
class IoVertex : public vcg::Vertex<IoTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::Qualityd,
                                    vcg::vertex::Color4b, vcg::vertex::TexCoord2f, vcg::vertex::BitFlags> {};
class IoFace : public vcg::Face<IoTypes, vcg::face::VertexRef, vcg::face::Normal3d, vcg::face::Qualityd,
                                vcg::face::Color4b, vcg::face::WedgeTexCoord2f, vcg::face::BitFlags> {};
class IoMesh : public vcg::tri::TriMesh<std::vector<IoVertex>, std::vector<IoFace>> {};

}  // namespace

void write_stl(const std::string& path, const Surface& s, const Eigen::VectorXd& face_quality) {
  IoMesh m;
  auto vi = vcg::tri::Allocator<IoMesh>::AddVertices(m, static_cast<size_t>(s.V.rows()));
  for (Eigen::Index i = 0; i < s.V.rows(); ++i, ++vi) vi->P() = vcg::Point3d(s.V(i, 0), s.V(i, 1), s.V(i, 2));
  auto fi = vcg::tri::Allocator<IoMesh>::AddFaces(m, static_cast<size_t>(s.F.rows()));
  for (Eigen::Index i = 0; i < s.F.rows(); ++i, ++fi)
    for (int k = 0; k < 3; ++k) fi->V(k) = &m.vert[static_cast<size_t>(s.F(i, k))];
  vcg::tri::UpdateNormal<IoMesh>::PerFaceNormalized(m);
  int mask = 0;
  if (face_quality.size() > 0) {
    write_face_results(m, face_quality, /*colourise=*/true, nullptr);
    mask |= vcg::tri::io::Mask::IOM_FACECOLOR;
  }
  const int err = vcg::tri::io::ExporterSTL<IoMesh>::Save(m, path.c_str(), true, mask);
  if (err != 0) throw std::runtime_error("cannot write " + path + ": " + vcg::tri::io::ExporterSTL<IoMesh>::ErrorMsg(err));
}

}  // namespace slim::vcg_adapters
