// 3MF through mesh_io: the build read onto the plate in millimetres and written back with the same
// unit, objects, names and transforms. The test files are made with lib3mf directly, and what
// mesh_io writes is opened with lib3mf directly, so each side is checked against the library, not
// against the other side.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>
#include <zip.h>

#include "Model/COM/NMR_DLLInterfaces.h"
#include "mesh_io/mesh_io.h"
#include "support/shapes.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

using Object = NMR::PLib3MFBase*;
struct Release {
  void operator()(Object h) const { NMR::lib3mf_release(h); }
};
using Handle = std::unique_ptr<NMR::PLib3MFBase, Release>;
using Transform = Eigen::Matrix<double, 3, 4>;

fs::path scratch_dir() {
  const fs::path dir = fs::temp_directory_path() / ("slim-3mf-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

NMR::MODELTRANSFORM lib3mf_transform(const Transform& m) {
  NMR::MODELTRANSFORM t;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) t.m_fFields[r][c] = static_cast<float>(m(r, c));
  return t;
}

Transform placement(double turn_deg, const Eigen::Vector3d& shift) {
  Transform m;
  m.leftCols<3>() = Eigen::AngleAxisd(turn_deg * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  m.col(3) = shift;
  // what lib3mf writes: each field as a float to 6 significant digits
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      std::ostringstream text;
      text << static_cast<float>(m(r, c));
      m(r, c) = std::stod(text.str());
    }
  return m;
}

Object add_mesh(Object model, const Surface& s, const char* name) {
  Object mesh = nullptr;
  EXPECT_EQ(NMR::lib3mf_model_addmeshobject(model, &mesh), LIB3MF_OK);
  std::vector<NMR::MODELMESHVERTEX> v(static_cast<size_t>(s.V.rows()));
  std::vector<NMR::MODELMESHTRIANGLE> f(static_cast<size_t>(s.F.rows()));
  for (Eigen::Index i = 0; i < s.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) v[size_t(i)].m_fPosition[k] = static_cast<float>(s.V(i, k));
  for (Eigen::Index i = 0; i < s.F.rows(); ++i)
    for (int k = 0; k < 3; ++k) f[size_t(i)].m_nIndices[k] = static_cast<DWORD>(s.F(i, k));
  EXPECT_EQ(NMR::lib3mf_meshobject_setgeometry(mesh, v.data(), DWORD(v.size()), f.data(), DWORD(f.size())), LIB3MF_OK);
  EXPECT_EQ(NMR::lib3mf_object_setnameutf8(mesh, name), LIB3MF_OK);
  return mesh;
}

// A plate in inches: the arch placed by an item turned and shifted, and the bunny-like blob inside
// a components object (shifted by its component), placed by an item of its own.
struct Plate {
  Surface arch = test::refined(test::arch(), 1), blob = test::refined(test::arch(), 0);
  Transform arch_item = placement(30, {1, 2, 0.5}), blob_component = placement(0, {4, 0, 0}),
            blob_item = placement(-45, {0, -3, 1});
};

void write_plate(const Plate& p, const fs::path& path) {
  Object model = nullptr;
  ASSERT_EQ(NMR::lib3mf_createmodel(&model), LIB3MF_OK);
  const Handle model_handle(model);
  ASSERT_EQ(NMR::lib3mf_model_setunit(model, NMR::MODELUNIT_INCH), LIB3MF_OK);
  const Handle arch(add_mesh(model, p.arch, "arch")), blob(add_mesh(model, p.blob, "blob"));
  Object group = nullptr, component = nullptr, item = nullptr;
  ASSERT_EQ(NMR::lib3mf_model_addcomponentsobject(model, &group), LIB3MF_OK);
  const Handle group_handle(group);
  NMR::MODELTRANSFORM t = lib3mf_transform(p.blob_component);
  ASSERT_EQ(NMR::lib3mf_componentsobject_addcomponent(group, blob.get(), &t, &component), LIB3MF_OK);
  NMR::lib3mf_release(component);
  t = lib3mf_transform(p.arch_item);
  ASSERT_EQ(NMR::lib3mf_model_addbuilditem(model, arch.get(), &t, &item), LIB3MF_OK);
  NMR::lib3mf_release(item);
  t = lib3mf_transform(p.blob_item);
  ASSERT_EQ(NMR::lib3mf_model_addbuilditem(model, group, &t, &item), LIB3MF_OK);
  NMR::lib3mf_release(item);
  Object writer = nullptr;
  ASSERT_EQ(NMR::lib3mf_model_querywriter(model, "3mf", &writer), LIB3MF_OK);
  const Handle writer_handle(writer);
  ASSERT_EQ(NMR::lib3mf_writer_writetofileutf8(writer, path.c_str()), LIB3MF_OK);
}

Eigen::RowVector3d placed(const Transform& m, const Eigen::RowVector3d& p) {
  return (m.leftCols<3>() * p.transpose() + m.col(3)).transpose();
}

// A 3MF opened with lib3mf: its unit, and per build item the mesh's vertices and the transform.
struct Opened {
  DWORD unit = 0;
  std::vector<Transform> items;
  std::vector<Points> vertices;
  std::vector<std::string> names;
};

Opened open_3mf(const fs::path& path) {
  Opened o;
  Object model = nullptr, reader = nullptr, items = nullptr;
  NMR::lib3mf_createmodel(&model);
  const Handle model_handle(model);
  NMR::lib3mf_model_queryreader(model, "3mf", &reader);
  const Handle reader_handle(reader);
  EXPECT_EQ(NMR::lib3mf_reader_readfromfileutf8(reader, path.c_str()), LIB3MF_OK);
  NMR::lib3mf_model_getunit(model, &o.unit);
  NMR::lib3mf_model_getbuilditems(model, &items);
  const Handle items_handle(items);
  BOOL more = 0;
  for (NMR::lib3mf_builditemiterator_movenext(items, &more); more; NMR::lib3mf_builditemiterator_movenext(items, &more)) {
    Object item = nullptr, mesh = nullptr;
    NMR::lib3mf_builditemiterator_getcurrent(items, &item);
    const Handle item_handle(item);
    NMR::lib3mf_builditem_getobjectresource(item, &mesh);
    const Handle mesh_handle(mesh);
    NMR::MODELTRANSFORM t;
    NMR::lib3mf_builditem_getobjecttransform(item, &t);
    Transform m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) m(r, c) = t.m_fFields[r][c];
    o.items.push_back(m);
    DWORD n = 0;
    NMR::lib3mf_meshobject_getvertexcount(mesh, &n);
    std::vector<NMR::MODELMESHVERTEX> v(n);
    NMR::lib3mf_meshobject_getvertices(mesh, v.data(), n, nullptr);
    Points V(n, 3);
    for (DWORD i = 0; i < n; ++i) V.row(i) << v[i].m_fPosition[0], v[i].m_fPosition[1], v[i].m_fPosition[2];
    o.vertices.push_back(V);
    char name[64] = {0};
    ULONG needed = 0;
    NMR::lib3mf_object_getnameutf8(mesh, name, sizeof name, &needed);
    o.names.push_back(name);
  }
  return o;
}

// Adds to the package's root relationships one to a thumbnail the package does not hold.
void add_dangling_thumbnail(const fs::path& path) {
  zip_t* archive = zip_open(path.c_str(), 0, nullptr);
  ASSERT_NE(archive, nullptr);
  const zip_int64_t index = zip_name_locate(archive, "_rels/.rels", 0);
  ASSERT_GE(index, 0);
  zip_stat_t stat;
  ASSERT_EQ(zip_stat_index(archive, zip_uint64_t(index), 0, &stat), 0);
  std::string rels(stat.size, '\0');
  zip_file_t* f = zip_fopen_index(archive, zip_uint64_t(index), 0);
  ASSERT_EQ(zip_fread(f, rels.data(), stat.size), zip_int64_t(stat.size));
  zip_fclose(f);
  const size_t end = rels.find("</Relationships>");
  ASSERT_NE(end, std::string::npos);
  static std::string with;  // libzip reads it at zip_close
  with = rels.substr(0, end) +
         "<Relationship Target=\"/Metadata/thumbnail.png\" Id=\"rel-9\" "
         "Type=\"http://schemas.openxmlformats.org/package/2006/relationships/metadata/thumbnail\"/>" + rels.substr(end);
  zip_source_t* text = zip_source_buffer(archive, with.data(), with.size(), 0);
  ASSERT_EQ(zip_file_replace(archive, zip_uint64_t(index), text, 0), 0);
  ASSERT_EQ(zip_close(archive), 0);
}

bool lib3mf_reads(const fs::path& path) {
  Object model = nullptr, reader = nullptr;
  NMR::lib3mf_createmodel(&model);
  const Handle model_handle(model);
  NMR::lib3mf_model_queryreader(model, "3mf", &reader);
  const Handle reader_handle(reader);
  return NMR::lib3mf_reader_readfromfileutf8(reader, path.c_str()) == LIB3MF_OK;
}

}  // namespace

// Every mesh the build places, through items and components, lands on the plate in millimetres.
TEST(ThreeMf, TheBuildIsReadOntoThePlateInMillimetres) {
  const fs::path dir = scratch_dir();
  const Plate p;
  write_plate(p, dir / "plate.3mf");
  const io::MeshFile file = io::read_mesh((dir / "plate.3mf").string());
  ASSERT_EQ(file.format, io::MeshFormat::ThreeMf);
  ASSERT_EQ(file.surface.V.rows(), p.arch.V.rows() + p.blob.V.rows());
  ASSERT_EQ(file.surface.F.rows(), p.arch.F.rows() + p.blob.F.rows());
  ASSERT_EQ(file.build.parts.size(), 2u);
  EXPECT_EQ(file.build.millimetres_per_unit, 25.4);
  EXPECT_EQ(file.build.parts[0].name, "arch");
  EXPECT_EQ(file.build.parts[1].name, "blob");
  const Eigen::Index n = p.arch.V.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector3d want = 25.4 * placed(p.arch_item, p.arch.V.row(i).cast<float>().cast<double>());
    ASSERT_LT((file.surface.V.row(i) - want).norm(), 1e-4) << i;
  }
  Transform blob_placement;
  blob_placement.leftCols<3>() = p.blob_item.leftCols<3>() * p.blob_component.leftCols<3>();
  blob_placement.col(3) = p.blob_item.leftCols<3>() * p.blob_component.col(3) + p.blob_item.col(3);
  for (Eigen::Index i = 0; i < p.blob.V.rows(); ++i) {
    const Eigen::RowVector3d want = 25.4 * placed(blob_placement, p.blob.V.row(i).cast<float>().cast<double>());
    ASSERT_LT((file.surface.V.row(n + i) - want).norm(), 1e-4) << i;
  }
  EXPECT_EQ(file.surface.F.topRows(p.arch.F.rows()), p.arch.F);
  EXPECT_EQ(file.surface.F.bottomRows(p.blob.F.rows()), (p.blob.F.array() + int(n)).matrix());
  fs::remove_all(dir);
}

// Written back: the same unit, one object per placed mesh with its name and placement, and each
// object's own vertices are where the moved plate puts them.
TEST(ThreeMf, WritingKeepsTheUnitTheObjectsAndTheirTransforms) {
  const fs::path dir = scratch_dir();
  const Plate p;
  write_plate(p, dir / "plate.3mf");
  const io::MeshFile file = io::read_mesh((dir / "plate.3mf").string());
  Points moved = file.surface.V;
  for (Eigen::Index i = 0; i < moved.rows(); ++i) moved.row(i) += Eigen::RowVector3d(0.1 * std::sin(double(i)), 0.2, -0.05 * i / moved.rows());
  io::write_mesh((dir / "out.3mf").string(), file, moved, {Eigen::VectorXd::Zero(moved.rows() == 0 ? 0 : file.surface.F.rows()), {}});
  const Opened o = open_3mf(dir / "out.3mf");
  EXPECT_EQ(o.unit, DWORD(NMR::MODELUNIT_INCH));
  ASSERT_EQ(o.items.size(), 2u);
  EXPECT_EQ(o.names, (std::vector<std::string>{"arch", "blob"}));
  Eigen::Index first = 0;
  for (size_t k = 0; k < 2; ++k) {
    // the placement to the 6 significant digits lib3mf writes; the vertices make up for the rounding
    EXPECT_LT((o.items[k] - file.build.parts[k].transform).cwiseAbs().maxCoeff(), 1e-5) << k;
    for (Eigen::Index i = 0; i < o.vertices[k].rows(); ++i)
      ASSERT_LT((25.4 * placed(o.items[k], o.vertices[k].row(i)) - moved.row(first + i)).norm(), 1e-4) << k << " " << i;
    first += o.vertices[k].rows();
  }
  const io::MeshFile back = io::read_mesh((dir / "out.3mf").string());
  EXPECT_EQ(back.surface.F, file.surface.F);
  EXPECT_LT((back.surface.V - moved).cwiseAbs().maxCoeff(), 1e-4);
  fs::remove_all(dir);
}

// From another format: one object in millimetres where the surface is, named after the file.
TEST(ThreeMf, AnotherFormatBecomesOneObjectInMillimetres) {
  const fs::path dir = scratch_dir();
  const Surface s = test::refined(test::arch(), 1);
  io::save_surface((dir / "arch.3mf").string(), s);
  const Opened o = open_3mf(dir / "arch.3mf");
  EXPECT_EQ(o.unit, DWORD(NMR::MODELUNIT_MILLIMETER));
  ASSERT_EQ(o.items.size(), 1u);
  EXPECT_EQ(o.names[0], "arch");
  EXPECT_EQ(o.items[0], Transform::Identity());
  EXPECT_LT((o.vertices[0] - s.V).cwiseAbs().maxCoeff(), 1e-5 * s.V.cwiseAbs().maxCoeff());
  fs::remove_all(dir);
}

// A root relationship to a part the package lacks (as PrusaSlicer's command line writes its
// thumbnail) does not stop the read; bytes that are no 3MF are refused with lib3mf's reason.
TEST(ThreeMf, AMissingThumbnailIsNoObstacleAndNonsenseIsRefused) {
  const fs::path dir = scratch_dir();
  const Surface s = test::refined(test::arch(), 1);
  const fs::path thumb = dir / "thumb.3mf";
  io::save_surface(thumb.string(), s);
  add_dangling_thumbnail(thumb);
  ASSERT_FALSE(lib3mf_reads(thumb));  // what is mended: the library alone refuses the package
  const Surface back = io::load_surface(thumb.string());
  EXPECT_EQ(back.F, s.F);
  EXPECT_LT((back.V - s.V).cwiseAbs().maxCoeff(), 1e-5 * s.V.cwiseAbs().maxCoeff());
  const fs::path bad = dir / "bad.3mf";
  std::ofstream(bad) << "not a zip at all";
  try {
    io::read_mesh(bad.string());
    FAIL() << "read nonsense";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cannot read " + bad.string() + ": not a readable 3MF file: ", 0), 0u) << e.what();
  }
  fs::remove_all(dir);
}
