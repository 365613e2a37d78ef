#include "mesh_io/mesh_io.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "core/geometry/welded_view.h"
#include "mesh_io/mesh_formats.h"
#include "vcg_adapters/displacement_ramp.h"
#include "vcg_adapters/stl_writer.h"

namespace slim::io {
namespace detail {

void refuse(const std::string& path, const std::string& why) { throw std::runtime_error("cannot read " + path + ": " + why); }

void write_failed(const std::string& path, const std::string& what) {
  const int error = errno;
  throw std::runtime_error("cannot write " + path + ": " + what + (error != 0 ? std::string(" (") + std::strerror(error) + ")" : ""));
}

void check_count(const std::string& path, const char* what, std::uint64_t count, std::uint64_t min_bytes,
                 std::uint64_t available) {
  constexpr std::uint64_t kIndexLimit = 2147483647;  // int indices, as VCG and the core use
  if (count > kIndexLimit)
    refuse(path, "it claims " + std::to_string(count) + " " + what + ", more than the 2147483647 this reader can index");
  if (min_bytes > 0 && count > available / min_bytes)
    refuse(path, "it claims " + std::to_string(count) + " " + what + ", but its " + std::to_string(available) +
                     " bytes of data can hold at most " + std::to_string(available / min_bytes) +
                     " (the file is truncated or its header is wrong)");
}

std::string shortest(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

Points vertex_normals(const Points& V, const Triangles& F) {
  Points n = Points::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d twice_area_normal = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) n.row(F(f, k)) += twice_area_normal;
  }
  for (Eigen::Index v = 0; v < n.rows(); ++v) {
    const double len = n.row(v).norm();
    if (len > 0.0) n.row(v) /= len;
  }
  return n;
}

Points normals_to_write(const MeshFile& source, const Points& V) {
  if (source.vertex.normal.rows() == 0) return Points(0, 3);
  if (V == source.surface.V) return source.vertex.normal;
  return vertex_normals(V, source.surface.F);
}

}  // namespace detail

namespace {

// STL: binary when the size matches the triangle count, else ASCII (every "vertex x y z"; three
// make a triangle). Each triangle's corners are read as the file gives them, then corners with
// equal coordinates become one vertex (in order of first appearance); the triangles keep the
// file's order. With a non-finite coordinate nothing is welded: the core then names it.
MeshFile read_stl(const std::string& path, const std::string& bytes) {
  std::vector<Eigen::Vector3d> corners;
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, sizeof count);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count)) {
    corners.reserve(3 * static_cast<size_t>(count));
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
      if (!(text >> x >> y >> z)) detail::refuse(path, "a vertex without three numbers");
      corners.emplace_back(x, y, z);
    }
    if ((corners.empty() || corners.size() % 3 != 0) && bytes.size() >= 84 && bytes.compare(0, 5, "solid") != 0)
      detail::refuse(path, "not an STL file: as binary STL its header claims " + std::to_string(count) +
                               " triangles, which take " + std::to_string(84 + 50 * std::uint64_t(count)) +
                               " bytes, but the file has " + std::to_string(bytes.size()));
    if (corners.empty() || corners.size() % 3 != 0)
      detail::refuse(path, "not an STL file (a binary one's size matches its triangle count, an ASCII one lists "
                           "three vertices per facet)");
  }
  Surface soup;
  soup.V.resize(static_cast<Eigen::Index>(corners.size()), 3);
  soup.F.resize(static_cast<Eigen::Index>(corners.size() / 3), 3);
  for (size_t i = 0; i < corners.size(); ++i) soup.V.row(static_cast<Eigen::Index>(i)) = corners[i].transpose();
  for (Eigen::Index f = 0; f < soup.F.rows(); ++f) soup.F.row(f) << int(3 * f), int(3 * f + 1), int(3 * f + 2);
  MeshFile file;
  file.format = MeshFormat::Stl;
  file.surface = weld_coincident(soup).surface;
  file.stl_corners = soup.V.rows();
  return file;
}

}  // namespace

MeshFormat format_of(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "off") return MeshFormat::Off;
  if (ext == "3mf") return MeshFormat::ThreeMf;
  throw std::runtime_error(path + ": unknown mesh format (the extension must be .ply, .stl, .obj, .off or .3mf)");
}

MeshFile read_mesh(const std::string& path) {
  format_of(path);  // an unknown extension is refused before the file is opened
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::refuse(path, "cannot open the file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) detail::refuse(path, "reading the file failed");
  return parse_mesh(path, bytes);
}

MeshFile parse_mesh(const std::string& path, const std::string& bytes) {
  switch (format_of(path)) {
    case MeshFormat::Ply: return detail::read_ply(path, bytes);
    case MeshFormat::Stl: return read_stl(path, bytes);
    case MeshFormat::Obj: return detail::read_obj(path, bytes);
    case MeshFormat::Off: return detail::read_off(path, bytes);
    case MeshFormat::ThreeMf: return detail::read_3mf(path, bytes);
  }
  throw std::logic_error("parse_mesh: unhandled format");
}

void write_mesh(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results) {
  const Surface s{V, source.surface.F};
  if (V.rows() != source.surface.V.rows()) throw std::invalid_argument("write_mesh: vertex count differs from the source's");
  if (results.quality.size() != 0 && results.quality.size() != s.F.rows())
    throw std::invalid_argument("write_mesh: face quality size differs from the face count");
  if (!results.selected.empty() && results.selected.size() != static_cast<size_t>(s.F.rows()))
    throw std::invalid_argument("write_mesh: selection size differs from the face count");
  check_surface(s);
  switch (format_of(path)) {
    case MeshFormat::Ply: return detail::write_ply(path, source, V, results);
    case MeshFormat::Stl: return vcg_adapters::write_stl(path, s, results.quality);
    case MeshFormat::Obj: return detail::write_obj(path, source, V);
    case MeshFormat::Off: return detail::write_off(path, source, V, results);
    case MeshFormat::ThreeMf: return detail::write_3mf(path, source, V, results);
  }
}

MeshFile with_displacement(const MeshFile& file, const Eigen::VectorXd& displacement_mm, double top_mm) {
  if (displacement_mm.size() != file.surface.V.rows()) throw std::invalid_argument("with_displacement: one value per vertex");
  MeshFile out = file;
  if (out.vertex.quality.size() == 0) out.vertex.quality = displacement_mm;
  if (out.vertex.colour.rows() == 0) {
    out.vertex.colour.resize(displacement_mm.size(), 4);
    for (Eigen::Index i = 0; i < displacement_mm.size(); ++i)
      out.vertex.colour.row(i) = vcg_adapters::displacement_ramp_colour(displacement_mm(i), top_mm);
  }
  return out;
}

Surface load_surface(const std::string& path, FaceExtras* extras) {
  MeshFile file = read_mesh(path);
  if (extras) *extras = FaceExtras{file.face.quality, file.face.selected};
  return std::move(file.surface);
}

void save_surface(const std::string& path, const Surface& s, const FaceExtras& extras) {
  MeshFile file;
  file.surface = s;
  write_mesh(path, file, s.V, extras);
}

}  // namespace slim::io
