// The local step's constraint pieces (core/optimizer/local_step.h): per tet, the faces it holds, with
// normals within kPieceMergeTolerance merged into one piece that carries their area.
#include <gtest/gtest.h>

#include <map>

#include "core/domain/embedded_domain.h"
#include "core/optimizer/local_step.h"
#include "support/shapes.h"

namespace slim {
namespace {

TEST(LocalStep, PiecesWithOneNormalAreOneConstraintCarryingTheirArea) {
  // A subdivided mushroom stored as floats (as MeshLab keeps a mesh): each original triangle
  // became 64 faces of one plane, whose normals differ by 1e-7 or so, many of them in one tet.
  Surface s = test::mushroom();  // turned and scaled: no coordinate a short binary fraction
  s.V = 1.37 * s.V * test::axis_angle(Eigen::Vector3d(0.3, 0.2, 0.9).normalized(), 0.41).transpose();
  s = test::refined(s, 3);
  s.V = s.V.cast<float>().cast<double>();
  const CheckedSurface checked(s);
  const EmbeddedDomain domain =
      embedded_domain(checked, Eigen::Vector3d::UnitZ(), DomainKind::Voxel, 24, 4e9, [](double, const std::string&) {});
  const Points n = face_normals(s);
  const std::vector<bool> plate(static_cast<size_t>(s.F.rows()), false);
  const TetPieces pieces = constraint_pieces(domain.embedding, domain.mesh.T.rows(), plate, n);
  const Embedding& e = domain.embedding;
  Eigen::Index merged = 0;
  for (Eigen::Index t = 0; t < domain.mesh.T.rows(); ++t) {
    const auto& mine = pieces[static_cast<size_t>(t)];
    double area = 0.0;
    for (int p = e.tet_face_offsets(t); p < e.tet_face_offsets(t + 1); ++p) {
      if (!(e.tet_face_areas(p) > 0.0)) continue;
      area += e.tet_face_areas(p);
      // Every piece's normal is within the tolerance of a kept one (or is one).
      bool near = false;
      for (const auto& [face, a] : mine)
        near = near || (n.row(face) - n.row(e.tet_faces(p))).norm() <= kPieceMergeTolerance;
      EXPECT_TRUE(near) << "tet " << t << " face " << e.tet_faces(p);
    }
    double kept_area = 0.0;
    for (size_t i = 0; i < mine.size(); ++i) {
      kept_area += mine[i].second;
      for (size_t j = 0; j < i; ++j)  // the kept normals are apart, in the order of their faces
        EXPECT_GT((n.row(mine[i].first) - n.row(mine[j].first)).norm(), kPieceMergeTolerance) << t;
      if (i > 0) {
        EXPECT_LT(mine[i - 1].first, mine[i].first) << t;
      }
    }
    EXPECT_NEAR(kept_area, area, 1e-12 * (1.0 + area)) << t;
    merged += (e.tet_face_offsets(t + 1) - e.tet_face_offsets(t)) - static_cast<Eigen::Index>(mine.size());
  }
  // Most pieces merge (69%; 27% at the minimal rotation's own tolerance, 1e-12).
  EXPECT_GT(merged, e.tet_faces.size() / 2) << "the faces of one plane should mostly merge";
}

}  // namespace
}  // namespace slim
