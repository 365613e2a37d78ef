// Mesh files through vcg_adapters/mesh_io: every format round-trips faces and positions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "support/shapes.h"
#include "vcg_adapters/mesh_io.h"

using namespace slim;
namespace fs = std::filesystem;

TEST(MeshIo, EveryFormatRoundTripsTheSurface) {
  const fs::path dir = fs::temp_directory_path() / ("slim-io-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Surface s = test::refined(test::arch(), 1);
  for (const std::string ext : {"ply", "stl", "obj", "off"}) {
    const std::string path = (dir / ("arch." + ext)).string();
    vcgx::save_surface(path, s);
    const Surface back = vcgx::load_surface(path);
    ASSERT_EQ(back.F.rows(), s.F.rows()) << ext;  // the OBJ reader once lost faces of vertex 1
    ASSERT_EQ(back.V.rows(), s.V.rows()) << ext;  // STL corners are welded back together
    EXPECT_NEAR(signed_volume(back), signed_volume(s), 1e-3 * signed_volume(s)) << ext;
  }
  fs::remove_all(dir);
}

TEST(MeshIo, ObjReaderTakesPolygonsSlashTokensAndRelativeIndices) {
  const fs::path path = fs::temp_directory_path() / ("slim-io-" + std::to_string(::getpid()) + ".obj");
  std::ofstream(path) << "# a unit square as a quad and a triangle with relative indices\n"
                         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                         "f 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -2//1 -1//1\n";
  const Surface s = vcgx::load_surface(path.string());
  ASSERT_EQ(s.F.rows(), 3);
  EXPECT_EQ(s.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(s.F.row(2), Eigen::RowVector3i(0, 2, 3));
  std::ofstream(path) << "v 0 0 0\nf 1 2 3\n";
  EXPECT_THROW(vcgx::load_surface(path.string()), std::runtime_error);
  fs::remove(path);
  EXPECT_THROW(vcgx::load_surface("/nonexistent/mesh.ply"), std::runtime_error);
}
