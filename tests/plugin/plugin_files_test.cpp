// What goes in comes out, through Support Slimming in MeshLab: a PLY with duplicate,
// coincident and unreferenced vertices, a non-manifold vertex, per-vertex colours and texture
// coordinates, imported as MeshLab imports it, gives a new layer with the input layer's vertex
// list in the same order and the same attributes; the input layer is left as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "filter_checks.h"
#include "harness.h"  // MeshLab's mesh types first: VCG's importer needs them

#include <wrap/io_trimesh/import_ply.h>
#include "support/attributed_mesh.h"

using namespace slim;
using slim::test::PluginHarness;
using slim::test::positions;
namespace fs = std::filesystem;

namespace {

// The PLY through VCG's PLY importer into a new layer, with the optional components its header
// asks for switched on first, as MeshLab's own File > Import Mesh does.
MeshModel* import_ply(MeshDocument& md, const std::string& path) {
  MeshModel* m = md.addNewMesh(QString(), "parts", true);
  int mask = 0;
  vcg::tri::io::ImporterPLY<CMeshO>::LoadMask(path.c_str(), mask);
  m->Enable(mask);
  EXPECT_EQ(vcg::tri::io::ImporterPLY<CMeshO>::Open(m->cm, path.c_str(), mask), 0) << path;
  vcg::tri::UpdateBounding<CMeshO>::Box(m->cm);
  vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(m->cm);
  return m;
}

std::vector<vcg::Color4b> colours(const MeshModel& m) {
  std::vector<vcg::Color4b> out;
  for (const auto& v : m.cm.vert) out.push_back(v.cC());
  return out;
}

std::vector<vcg::Point2f> texcoords(const MeshModel& m) {
  std::vector<vcg::Point2f> out;
  for (const auto& v : m.cm.vert) out.push_back(v.cT().P());
  return out;
}

std::vector<int> face_indices(const MeshModel& m) {
  std::vector<int> out;
  for (const auto& f : m.cm.face)
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<int>(f.cV(k) - &m.cm.vert[0]));
  return out;
}

class PluginFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slim-plugin-files-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    test::write_attributed_ply((dir_ / "parts.ply").string(), mesh_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  const test::AttributedMesh mesh_ = test::attributed_mesh();
};

}  // namespace

TEST_F(PluginFiles, TheSlimmedLayerKeepsTheVertexListItsOrderAndItsAttributes) {
  PluginHarness h;
  ASSERT_TRUE(h.ok()) << h.error().toStdString();
  for (const int iterations : {0, 8}) {
    MeshDocument md;
    MeshModel* input = import_ply(md, (dir_ / "parts.ply").string());
    ASSERT_EQ(input->cm.vn, mesh_.surface.V.rows());
    ASSERT_TRUE(input->hasDataMask(MeshModel::MM_VERTTEXCOORD));
    const auto original = positions(*input);
    const auto original_colours = colours(*input);
    const auto original_texcoords = texcoords(*input);
    RichParameterList params = h.defaults("Support Slimming", md);
    params.setValue("maxIterations", IntValue(iterations));
    // Printed along (1.4, 0, 1) the boxes' faces overhang by a few degrees, which 8 small
    // steps make safe (aimed 10 degrees past the threshold, 4 save nothing yet), saving support.
    // (Upright their flat undersides need 45 degrees, which no iterate of 8 reaches; along
    // (0.8, 0.5, 1) the boxes stand on their corners, whose columns stay whatever the faces do:
    // either way the input would come back untouched, and nothing moved would be tested.)
    params.setValue("printDirection", Point3fValue(vcg::Point3f(1.4f, 0.0f, 1.0f)));
    ASSERT_TRUE(h.apply("Support Slimming", md, params)) << h.lastError().toStdString();
    ASSERT_EQ(md.meshList.size(), 2);
    const MeshModel& out = *md.mm();
    ASSERT_NE(&out, input);

    // The arrays, element for element: the same vertices in the same order, the same faces.
    ASSERT_EQ(out.cm.vn, input->cm.vn) << iterations;
    ASSERT_EQ(out.cm.vert.size(), input->cm.vert.size()) << iterations;
    EXPECT_EQ(face_indices(out), face_indices(*input)) << iterations;
    EXPECT_TRUE(colours(out) == original_colours) << iterations;
    EXPECT_TRUE(texcoords(out) == original_texcoords) << iterations;
    const auto moved = positions(out);
    if (iterations == 0) {
      EXPECT_TRUE(moved == original);
    } else {
      float most = 0;
      for (size_t i = 0; i < moved.size(); ++i) most = std::max(most, (moved[i] - original[i]).Norm());
      EXPECT_GT(most, 1e-3f) << "the overhanging boxes moved";
    }
    // Coincident vertices are one point for the core: they move together, no seam opens.
    EXPECT_EQ(moved[static_cast<size_t>(mesh_.seam_copy)], moved[static_cast<size_t>(mesh_.seam_original)]);
    EXPECT_EQ(moved[static_cast<size_t>(mesh_.unreferenced_copy)], moved[static_cast<size_t>(mesh_.seam_original)]);
    for (size_t v = 0; v < original.size(); ++v)
      if (original[v] == original[static_cast<size_t>(mesh_.coincident_corner)]) {
        EXPECT_EQ(moved[v], moved[static_cast<size_t>(mesh_.coincident_corner)]) << v;
      }
    // The input layer is as it was.
    EXPECT_TRUE(positions(*input) == original);
    EXPECT_TRUE(colours(*input) == original_colours);
    EXPECT_TRUE(h.logLines().join("\n").contains(iterations == 0 ? "solver none (no iteration ran)" : "solver "));
  }
}
