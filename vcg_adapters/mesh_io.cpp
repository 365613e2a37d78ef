#include "vcg_adapters/mesh_io.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/clean.h>
#include <wrap/io_trimesh/export.h>
#include <wrap/io_trimesh/import.h>

#include "vcg_adapters/surface_adapter.h"

namespace slim::vcgx {
namespace {

// Writing: the OBJ exporter needs a per-vertex normal type.
class IoVertex;
class IoFace;
struct IoTypes : vcg::UsedTypes<vcg::Use<IoVertex>::AsVertexType, vcg::Use<IoFace>::AsFaceType> {};
class IoVertex : public vcg::Vertex<IoTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::Qualityd,
                                    vcg::vertex::Color4b, vcg::vertex::BitFlags> {};
class IoFace : public vcg::Face<IoTypes, vcg::face::VertexRef, vcg::face::Normal3d, vcg::face::Qualityd,
                                vcg::face::Color4b, vcg::face::BitFlags> {};
class IoMesh : public vcg::tri::TriMesh<std::vector<IoVertex>, std::vector<IoFace>> {};

// VCG 2020.09's OBJ reader turns face indices 0-based in SplitToken and then GoodObjIndex rejects
// index 0, so it silently drops every face that uses the file's first vertex (MeshLab's own OBJ
// import shares the bug). OBJ is simple enough to read here: v and f records, "v/t/n" tokens,
// negative (relative) indices, polygons fanned into triangles; everything else is ignored.
Surface load_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path + ": cannot open the file");
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  std::string line;
  for (long lineno = 1; std::getline(in, line); ++lineno) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      Eigen::Vector3d p;
      if (!(ls >> p.x() >> p.y() >> p.z())) throw std::runtime_error("cannot read " + path + ": bad vertex on line " + std::to_string(lineno));
      v.push_back(p);
    } else if (tag == "f") {
      std::vector<int> poly;
      std::string token;
      while (ls >> token) {
        long idx = 0;
        try {
          idx = std::stol(token.substr(0, token.find('/')));
        } catch (const std::exception&) {
          throw std::runtime_error("cannot read " + path + ": bad face index '" + token + "' on line " + std::to_string(lineno));
        }
        idx = idx < 0 ? static_cast<long>(v.size()) + idx : idx - 1;
        if (idx < 0 || idx >= static_cast<long>(v.size()))
          throw std::runtime_error("cannot read " + path + ": face index out of range on line " + std::to_string(lineno));
        poly.push_back(static_cast<int>(idx));
      }
      for (size_t k = 2; k < poly.size(); ++k) f.emplace_back(poly[0], poly[k - 1], poly[k]);
    }
  }
  Surface s;
  s.V.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i) s.V.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  s.F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (size_t i = 0; i < f.size(); ++i) s.F.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return s;
}

// VCG 2020.09's STL reader runs strlen over the 80-byte binary header, which need not hold a zero
// byte (VCG's own exporter fills it with spaces): a stack over-read on nearly every binary STL,
// which AddressSanitizer reports. It also dereferences a null FILE* for a missing file. STL is
// simple enough to read here: binary when the size matches the triangle count, else ASCII (every
// "vertex x y z"; three make a triangle). Each triangle gets its own three corners, as in the file.
void load_stl(const std::string& path, IoMesh& m) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": cannot open the file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<vcg::Point3d> corners;
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, sizeof count);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count)) {
    for (std::uint32_t t = 0; t < count; ++t) {
      float xyz[12];  // the facet normal, then three corners; the 2-byte attribute is ignored
      std::memcpy(xyz, bytes.data() + 84 + 50 * static_cast<size_t>(t), sizeof xyz);
      for (int k = 1; k <= 3; ++k) corners.emplace_back(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
    }
  } else {
    std::istringstream text(bytes);
    std::string token;
    while (text >> token) {
      if (token != "vertex") continue;
      double x, y, z;
      if (!(text >> x >> y >> z)) throw std::runtime_error("cannot read " + path + ": a vertex without three numbers");
      corners.emplace_back(x, y, z);
    }
    if (corners.empty() || corners.size() % 3 != 0)
      throw std::runtime_error("cannot read " + path +
                               ": not an STL file (a binary one's size matches its triangle count, an ASCII one "
                               "lists three vertices per facet)");
  }
  auto vi = vcg::tri::Allocator<IoMesh>::AddVertices(m, corners.size());
  for (const vcg::Point3d& p : corners) (vi++)->P() = p;
  auto fi = vcg::tri::Allocator<IoMesh>::AddFaces(m, corners.size() / 3);
  for (size_t f = 0; f < corners.size() / 3; ++f, ++fi)
    for (int k = 0; k < 3; ++k) fi->V(k) = &m.vert[3 * f + static_cast<size_t>(k)];
}

bool has_extension(const std::string& path, const std::string& ext) {
  if (path.size() < ext.size()) return false;
  std::string tail = path.substr(path.size() - ext.size());
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == ext;
}

}  // namespace

Surface load_surface(const std::string& path, FaceExtras* extras) {
  if (has_extension(path, ".obj")) {
    if (extras) *extras = FaceExtras{};
    return load_obj(path);
  }
  IoMesh m;
  int mask = 0;
  if (has_extension(path, ".stl")) {
    load_stl(path, m);
  } else {
    const int err = vcg::tri::io::Importer<IoMesh>::Open(m, path.c_str(), mask);
    if (err != 0 && vcg::tri::io::Importer<IoMesh>::ErrorCritical(err))
      throw std::runtime_error("cannot read " + path + ": " + vcg::tri::io::Importer<IoMesh>::ErrorMsg(err));
  }
  // STL stores each triangle's corners separately; weld them so the surface is connected. Not
  // with a NaN coordinate: the weld sorts by position, and NaN breaks the ordering std::sort
  // relies on (undefined behaviour); the core then refuses the file, naming the vertex.
  bool finite = true;
  for (const auto& v : m.vert) finite = finite && std::isfinite(v.cP()[0] + v.cP()[1] + v.cP()[2]);
  if (finite) {
    vcg::tri::Clean<IoMesh>::RemoveDuplicateVertex(m);
    vcg::tri::Allocator<IoMesh>::CompactEveryVector(m);
  }
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
