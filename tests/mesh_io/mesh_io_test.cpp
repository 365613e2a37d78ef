// Mesh files through vcg_adapters/mesh_io: every format round-trips faces and positions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

#include "mesh_io/mesh_io.h"
#include "support/shapes.h"

using namespace slim;
namespace fs = std::filesystem;

TEST(MeshIo, EveryFormatRoundTripsTheSurface) {
  const fs::path dir = fs::temp_directory_path() / ("slim-io-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Surface s = test::refined(test::arch(), 1);
  for (const std::string ext : {"ply", "stl", "obj", "off"}) {
    const std::string path = (dir / ("arch." + ext)).string();
    io::save_surface(path, s);
    const Surface back = io::load_surface(path);
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
  const Surface s = io::load_surface(path.string());
  ASSERT_EQ(s.F.rows(), 3);
  EXPECT_EQ(s.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(s.F.row(2), Eigen::RowVector3i(0, 2, 3));
  std::ofstream(path) << "v 0 0 0\nf 1 2 3\n";
  EXPECT_THROW(io::load_surface(path.string()), std::runtime_error);
  fs::remove(path);
  EXPECT_THROW(io::load_surface("/nonexistent/mesh.ply"), std::runtime_error);
}

namespace {
fs::path scratch_dir() {
  const fs::path dir = fs::temp_directory_path() / ("slim-io-attr-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A surface with every attribute MeshFile carries, none of them alike across vertices or faces.
io::MeshFile with_every_attribute(const Surface& s) {
  io::MeshFile m;
  m.surface = s;
  const Eigen::Index nv = s.V.rows(), nf = s.F.rows();
  m.vertex.colour.resize(nv, 4);
  m.vertex.texcoord.resize(nv, 2);
  m.vertex.normal.resize(nv, 3);
  m.vertex.quality = Eigen::VectorXd::LinSpaced(nv, -2.5, 7.25);
  for (Eigen::Index i = 0; i < nv; ++i) {
    m.vertex.colour.row(i) << static_cast<unsigned char>(i), static_cast<unsigned char>(2 * i), 7, 250;
    m.vertex.texcoord.row(i) << i / 8.0, 1.0 - i / 16.0;
    m.vertex.normal.row(i) = Eigen::RowVector3d(1.0 + i, 2, 3).normalized();
    m.vertex.selected.push_back(i % 3 == 0);
  }
  m.face.colour.resize(nf, 4);
  m.face.wedge_texcoord.resize(nf, 6);
  m.face.quality = Eigen::VectorXd::LinSpaced(nf, 0.0, 1.0);
  m.face.texture = Eigen::VectorXi::Zero(nf);
  for (Eigen::Index f = 0; f < nf; ++f) {
    m.face.colour.row(f) << 90, static_cast<unsigned char>(f), 3, 255;
    for (int k = 0; k < 6; ++k) m.face.wedge_texcoord(f, k) = (f + k) / 32.0;
    m.face.selected.push_back(f % 2 == 1);
  }
  m.textures = {"skin.png"};
  return m;
}
}  // namespace

TEST(MeshIo, PlyCarriesEveryAttributeThrough) {
  const fs::path dir = scratch_dir();
  const io::MeshFile m = with_every_attribute(test::box({0, 0, 0}, {10, 10, 10}));
  const std::string path = (dir / "box.ply").string();
  io::write_mesh(path, m, m.surface.V);
  const io::MeshFile back = io::read_mesh(path);
  EXPECT_EQ(back.surface.V, m.surface.V);
  EXPECT_EQ(back.surface.F, m.surface.F);
  EXPECT_EQ(back.vertex.colour, m.vertex.colour);
  EXPECT_EQ(back.vertex.normal, m.vertex.normal);  // nothing moved: the file's own
  EXPECT_EQ(back.vertex.texcoord, m.vertex.texcoord);
  EXPECT_EQ(back.vertex.quality, m.vertex.quality);
  EXPECT_EQ(back.vertex.selected, m.vertex.selected);
  EXPECT_EQ(back.face.colour, m.face.colour);
  EXPECT_EQ(back.face.quality, m.face.quality);
  EXPECT_EQ(back.face.selected, m.face.selected);
  EXPECT_EQ(back.face.wedge_texcoord, m.face.wedge_texcoord);
  EXPECT_EQ(back.textures, m.textures);

  // A run's results replace face quality, colour and selection; nothing else.
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(m.surface.F.rows(), -1.0, 1.0);
  const std::vector<bool> risky(static_cast<size_t>(m.surface.F.rows()), true);
  io::write_mesh(path, m, m.surface.V, {q, risky});
  const io::MeshFile run = io::read_mesh(path);
  EXPECT_EQ(run.face.quality, q);
  EXPECT_EQ(run.face.selected, risky);
  EXPECT_NE(run.face.colour, m.face.colour);
  EXPECT_EQ(run.face.colour(0, 0), 255);  // -1: the red end of the ramp
  EXPECT_EQ(run.vertex.colour, m.vertex.colour);
  EXPECT_EQ(run.face.wedge_texcoord, m.face.wedge_texcoord);
  fs::remove_all(dir);
}

TEST(MeshIo, NormalsAreRecomputedWhereAVertexMoved) {
  const fs::path dir = scratch_dir();
  const io::MeshFile m = with_every_attribute(test::box({0, 0, 0}, {10, 10, 10}));
  Points moved = m.surface.V;
  moved.col(2) *= 2.0;  // taller: the faces' directions stay, the file's made-up normals do not fit
  for (const std::string ext : {"ply", "off"}) {
    const std::string path = (dir / ("box." + ext)).string();
    io::write_mesh(path, m, moved);
    const io::MeshFile back = io::read_mesh(path);
    ASSERT_EQ(back.vertex.normal.rows(), moved.rows()) << ext;
    for (Eigen::Index v = 0; v < moved.rows(); ++v) {
      EXPECT_NEAR(back.vertex.normal.row(v).norm(), 1.0, 1e-12) << ext;
      // A box corner's normal points away from the centre in every axis.
      const Eigen::RowVector3d out = moved.row(v) - Eigen::RowVector3d(5, 5, 10);
      EXPECT_GT(back.vertex.normal.row(v).cwiseProduct(out).minCoeff(), 0.0) << ext << " vertex " << v;
    }
  }
  fs::remove_all(dir);
}

TEST(MeshIo, ObjIsWrittenBackLineForLineWithNewCoordinatesAndNormals) {
  const fs::path dir = scratch_dir();
  const fs::path in = dir / "tri.obj", out = dir / "tri_out.obj";
  std::ofstream(in) << "# a triangle and a quad\nmtllib m.mtl\nv 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                       "vt 0 0\nvn 0 0 1\nvn 0 0 -1\ng a\nusemtl red\nf 1/1/1 2/1/1 3/1/1\nf -4//2 -2//2 -1//2 -3//2\n";
  const io::MeshFile m = io::read_mesh(in.string());
  ASSERT_EQ(m.surface.F.rows(), 3);  // the quad as a fan of two
  EXPECT_EQ(m.surface.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.surface.F.row(2), Eigen::RowVector3i(0, 3, 1));
  Points moved = m.surface.V;
  moved(0, 2) = 0.125;
  io::write_mesh(out.string(), m, moved);
  // Every line as it was but the moved vertex's, whose colour stays; the two normals replaced by
  // one per vertex, and each corner's normal index by its vertex's.
  std::istringstream lines(text_of(out));
  std::string line, kept;
  int normals = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("vn ", 0) == 0) {
      double x, y, z;
      std::istringstream(line.substr(3)) >> x >> y >> z;
      EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 1e-12) << line;
      ++normals;
    } else {
      kept += line + "\n";
    }
  }
  EXPECT_EQ(normals, 4);
  EXPECT_EQ(kept,
            "# a triangle and a quad\nmtllib m.mtl\nv 0 0 0.125 1 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\ng a\n"
            "usemtl red\nf 1/1/1 2/1/2 3/1/3\nf 1//1 3//3 4//4 2//2\n");
  // Unmoved, the file comes back byte for byte.
  io::write_mesh(out.string(), m, m.surface.V);
  EXPECT_EQ(text_of(out), text_of(in));
  fs::remove_all(dir);
}

TEST(MeshIo, PolygonsBecomeFansAndBothPlyEndiansRead) {
  const fs::path dir = scratch_dir();
  const std::string header = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nproperty uchar red\n"
                             "property uchar green\nproperty uchar blue\nend_header\n";
  std::ofstream(dir / "quad.ply") << "ply\nformat ascii 1.0\n" << header << "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 10 20 30\n";
  std::ofstream(dir / "quad.off") << "COFF\n4 1 0\n0 0 0 1 2 3\n1 0 0 1 2 3\n1 1 0 1 2 3\n0 1 0 1 2 3\n4 0 1 2 3 10 20 30\n";
  // The same quad, big-endian binary.
  std::string big = "ply\nformat binary_big_endian 1.0\n" + header;
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  auto put_big = [&](const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    for (size_t k = n; k-- > 0;) big += c[k];
  };
  for (const auto& v : xyz)
    for (float x : v) put_big(&x, 4);
  big += '\x04';
  for (std::int32_t i = 0; i < 4; ++i) put_big(&i, 4);
  big += std::string("\x0a\x14\x1e");
  std::ofstream(dir / "quad_big.ply", std::ios::binary) << big;
  for (const char* name : {"quad.ply", "quad.off", "quad_big.ply"}) {
    const io::MeshFile m = io::read_mesh((dir / name).string());
    ASSERT_EQ(m.surface.F.rows(), 2) << name;
    EXPECT_EQ(m.surface.F.row(0), Eigen::RowVector3i(0, 1, 2)) << name;
    EXPECT_EQ(m.surface.F.row(1), Eigen::RowVector3i(0, 2, 3)) << name;
    ASSERT_EQ(m.face.colour.rows(), 2) << name;
    EXPECT_EQ(m.face.colour.row(1), (Eigen::Matrix<unsigned char, 1, 4>(10, 20, 30, 255))) << name;
    EXPECT_EQ(m.surface.V.row(2), Eigen::RowVector3d(1, 1, 0)) << name;
  }
  fs::remove_all(dir);
}

TEST(MeshIo, StlCornersWeldInTheOrderTheyFirstAppear) {
  const fs::path dir = scratch_dir();
  const std::string path = (dir / "two.stl").string();
  std::ofstream(path) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                         "endfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\n"
                         "endfacet\nendsolid t\n";
  const io::MeshFile m = io::read_mesh(path);
  EXPECT_EQ(m.stl_corners, 6);
  ASSERT_EQ(m.surface.V.rows(), 4);
  EXPECT_EQ(m.surface.V.row(3), Eigen::RowVector3d(1, 1, 0));
  EXPECT_EQ(m.surface.F.row(1), Eigen::RowVector3i(1, 3, 2));
  fs::remove_all(dir);
}

TEST(MeshIo, ConversionsCarryWhatTheTargetFormatHolds) {
  const fs::path dir = scratch_dir();
  const fs::path obj = dir / "c.obj";
  std::ofstream(obj) << "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nvt 0.5 0.25\nvt 1 0\nf 1/1 2/2 3/1\n";
  const io::MeshFile m = io::read_mesh(obj.string());
  ASSERT_EQ(m.vertex.colour.rows(), 3);
  ASSERT_EQ(m.face.wedge_texcoord.rows(), 1);
  EXPECT_EQ(m.face.wedge_texcoord.row(0), (Eigen::Matrix<double, 1, 6>() << 0.5, 0.25, 1, 0, 0.5, 0.25).finished());
  for (const std::string ext : {"ply", "off", "obj"}) {
    io::MeshFile source = m;
    if (ext == "obj") source.obj.reset();  // written from the model, not from the OBJ's lines
    const std::string path = (dir / ("c_out." + ext)).string();
    io::write_mesh(path, source, m.surface.V);
    const io::MeshFile back = io::read_mesh(path);
    EXPECT_EQ(back.surface.V, m.surface.V) << ext;
    EXPECT_EQ(back.surface.F, m.surface.F) << ext;
    EXPECT_EQ(back.vertex.colour, m.vertex.colour) << ext;
    if (ext != "off") {
      EXPECT_EQ(back.face.wedge_texcoord.cast<float>(), m.face.wedge_texcoord.cast<float>()) << ext;
    }
  }
  fs::remove_all(dir);
}
