#include "layers.h"

#include <vcg/complex/complex.h>

#include "meshlab_api.h"  // MeshDocument and MeshModel of the API being built

namespace slim::test {

MeshModel* add_layer(MeshDocument& md, const Surface& s, const QString& label) {
  MeshModel* m = md.addNewMesh(QString(), label, true);
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(m->cm, static_cast<size_t>(s.V.rows()));
  for (Eigen::Index i = 0; i < s.V.rows(); ++i, ++vi)
    vi->P() = vcg::Point3f(float(s.V(i, 0)), float(s.V(i, 1)), float(s.V(i, 2)));
  auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(m->cm, static_cast<size_t>(s.F.rows()));
  for (Eigen::Index i = 0; i < s.F.rows(); ++i, ++fi)
    for (int k = 0; k < 3; ++k) fi->V(k) = &m->cm.vert[static_cast<size_t>(s.F(i, k))];
  vcg::tri::UpdateBounding<CMeshO>::Box(m->cm);
  vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(m->cm);
  return m;
}

}  // namespace slim::test
