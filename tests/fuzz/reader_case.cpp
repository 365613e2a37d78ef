#include "fuzz/reader_case.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "mesh_io/mesh_io.h"
#include "support/bad_inputs.h"
#include "support/shapes.h"

namespace slim::fuzz {
namespace {

const char* const kExtensions[4] = {"ply", "stl", "obj", "off"};

template <class M>
bool rows_ok(const M& m, Eigen::Index rows) {
  return m.rows() == 0 || m.rows() == rows;
}

// Equal shapes and values, NaN counting as equal to NaN (a file may hold NaN qualities or normals).
template <class A, class B>
bool same(const A& a, const B& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  return (a.array() == b.array() || (a.array() != a.array() && b.array() != b.array())).all();
}

// What a well-formed MeshFile must satisfy, whatever the bytes were.
std::string shape_problem(const io::MeshFile& f) {
  const Eigen::Index nv = f.surface.V.rows(), nf = f.surface.F.rows();
  if (f.surface.V.cols() != 3 || f.surface.F.cols() != 3) return "the surface is not #V by 3 and #F by 3";
  if (nf > 0 && (f.surface.F.minCoeff() < 0 || f.surface.F.maxCoeff() >= nv)) return "a face index outside the vertices";
  const io::VertexAttributes& v = f.vertex;
  if (!rows_ok(v.colour, nv) || !rows_ok(v.normal, nv) || !rows_ok(v.texcoord, nv) || !rows_ok(v.quality, nv) ||
      !(v.selected.empty() || v.selected.size() == static_cast<size_t>(nv)))
    return "a vertex attribute with a row count other than #V";
  const io::FaceAttributes& a = f.face;
  if (!rows_ok(a.colour, nf) || !rows_ok(a.quality, nf) || !rows_ok(a.wedge_texcoord, nf) ||
      a.texture.size() != a.wedge_texcoord.rows() || !(a.selected.empty() || a.selected.size() == static_cast<size_t>(nf)))
    return "a face attribute with a row count other than #F";
  return "";
}

// Written back in its own format and read again: the same lists and attributes.
std::string round_trip_problem(const std::string& ext, const io::MeshFile& f) {
  if (!f.surface.V.allFinite() || f.surface.V.rows() == 0 || f.surface.F.rows() == 0) return "";
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("slim-reader-fuzz-" + std::to_string(::getpid()) + "." + ext);
  io::MeshFile back;
  try {
    io::write_mesh(path.string(), f, f.surface.V);
    back = io::read_mesh(path.string());
  } catch (const std::exception& e) {
    std::filesystem::remove(path);
    return std::string("writing it back and reading it again failed: ") + e.what();
  }
  std::filesystem::remove(path);
  if (back.surface.F.rows() != f.surface.F.rows()) return "read back, the face count differs";
  if (ext == "stl") {  // corners, as the floats STL stores
    for (Eigen::Index t = 0; t < f.surface.F.rows(); ++t)
      for (int k = 0; k < 3; ++k)
        if (f.surface.V.row(f.surface.F(t, k)).cast<float>() != back.surface.V.row(back.surface.F(t, k)).cast<float>())
          return "read back, an STL corner moved";
    return "";
  }
  if (back.surface.V != f.surface.V) return "read back, the vertex list differs";
  if (back.surface.F != f.surface.F) return "read back, the face list differs";
  if (back.vertex.colour != f.vertex.colour) return "read back, the vertex colours differ";
  if (!same(back.vertex.normal, f.vertex.normal)) return "read back, the vertex normals differ";
  if (!same(back.vertex.texcoord.cast<float>(), f.vertex.texcoord.cast<float>())) return "read back, the texture coordinates differ";
  if (ext == "obj") {
    if (!same(back.face.wedge_texcoord, f.face.wedge_texcoord)) return "read back, the corners' texture coordinates differ";
    return "";
  }
  if (back.face.colour != f.face.colour) return "read back, the face colours differ";
  if (ext == "ply") {
    if (!same(back.vertex.quality, f.vertex.quality) || !same(back.face.quality, f.face.quality))
      return "read back, a quality differs";
    if (back.vertex.selected != f.vertex.selected || back.face.selected != f.face.selected) return "read back, a selection differs";
    if (!same(back.face.wedge_texcoord.cast<float>(), f.face.wedge_texcoord.cast<float>()) || back.face.texture != f.face.texture)
      return "read back, the corners' texture coordinates differ";
  }
  return "";
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

std::string run_reader_case(const std::uint8_t* data, size_t size) {
  const std::string ext = kExtensions[size > 0 ? data[0] % 4 : 0];
  const std::string name = "fuzz." + ext;
  const std::string bytes = size > 0 ? std::string(reinterpret_cast<const char*>(data) + 1, size - 1) : std::string();
  io::MeshFile f;
  try {
    f = io::parse_mesh(name, bytes);
  } catch (const std::runtime_error& e) {
    const std::string why = e.what();
    if (why.rfind("cannot read " + name + ": ", 0) != 0) return "a refusal that does not name the file: " + why;
    if (why.find('\n') != std::string::npos) return "a refusal of more than one line: " + why;
    return "";
  } catch (const std::exception& e) {
    return std::string("an exception other than std::runtime_error: ") + e.what();
  }
  const std::string shape = shape_problem(f);
  return shape.empty() ? round_trip_problem(ext, f) : shape;
}

std::vector<std::uint8_t> encode_reader_case(const std::string& extension, const std::string& file_bytes) {
  std::uint8_t selector = 0;
  for (std::uint8_t k = 0; k < 4; ++k)
    if (extension == kExtensions[k]) selector = k;
  std::vector<std::uint8_t> out(file_bytes.size() + 1);
  out[0] = selector;
  std::copy(file_bytes.begin(), file_bytes.end(), out.begin() + 1);
  return out;
}

std::vector<std::pair<std::string, std::vector<std::uint8_t>>> reader_seeds() {
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> seeds;
  for (const test::BadFile& f : test::bad_files())
    if (f.extension == "ply" || f.extension == "stl" || f.extension == "obj" || f.extension == "off")
      seeds.emplace_back(f.name + ".bin", encode_reader_case(f.extension, f.bytes));

  // Well-formed files, through the project's own writers where it has them.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("slim-seeds-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Surface t = test::t_shape();
  auto written = [&](const std::string& file, const io::MeshFile& m, const io::FaceExtras& extras) {
    const std::string path = (dir / file).string();
    io::write_mesh(path, m, m.surface.V, extras);
    return file_bytes(path);
  };
  io::MeshFile coloured;
  coloured.surface = t;
  coloured.vertex.colour = io::Rgba::Constant(t.V.rows(), 4, 200);
  coloured.vertex.normal = Points::Zero(t.V.rows(), 3);
  coloured.vertex.normal.col(2).setOnes();
  const io::FaceExtras results{Eigen::VectorXd::LinSpaced(t.F.rows(), -1, 1), std::vector<bool>(static_cast<size_t>(t.F.rows()), true)};
  seeds.emplace_back("valid_binary_ply.bin", encode_reader_case("ply", written("t.ply", coloured, results)));
  seeds.emplace_back("valid_binary_stl.bin", encode_reader_case("stl", written("t.stl", coloured, {})));
  seeds.emplace_back("valid_off_colours_normals.bin", encode_reader_case("off", written("t.off", coloured, results)));
  seeds.emplace_back("valid_plain_obj.bin", encode_reader_case("obj", written("t.obj", coloured, {})));
  test::write_ascii_ply((dir / "a.ply").string(), t);
  seeds.emplace_back("valid_ascii_ply.bin", encode_reader_case("ply", file_bytes((dir / "a.ply").string())));
  std::filesystem::remove_all(dir);

  // Hand-written: encodings and records the writers above do not produce.
  seeds.emplace_back("valid_big_endian_ply.bin",
                     encode_reader_case("ply", std::string("ply\nformat binary_big_endian 1.0\ncomment TextureFile t.png\n"
                                                           "element vertex 3\nproperty double x\nproperty double y\n"
                                                           "property double z\nproperty uchar red\nproperty uchar green\n"
                                                           "property uchar blue\nelement face 1\nproperty list uchar "
                                                           "uint vertex_indices\nproperty list uchar float texcoord\n"
                                                           "end_header\n") +
                                                   std::string(3 * 27, '\0') + std::string("\x03\0\0\0\0\0\0\0\x01\0\0\0\x02\x06", 14) +
                                                   std::string(24, '\0')));
  seeds.emplace_back("valid_ascii_stl.bin",
                     encode_reader_case("stl", "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 10 0\n"
                                               "vertex 10 0 0\nendloop\nendfacet\nendsolid t\n"));
  seeds.emplace_back("valid_obj_records.bin",
                     encode_reader_case("obj", "# a quad and a triangle\nmtllib t.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\n"
                                               "v 1 1 0 0 0 1\nv 0 1 0 1 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\ng part\n"
                                               "usemtl red\ns 1\nf 1/1/1 2/2/1 3/3/1 4/1/1\nf -4//1 -2//1 -1//1\nl 1 2\n"));
  seeds.emplace_back("valid_off_polygon.bin",
                     encode_reader_case("off", "STCOFF 4 2 0 # counts on the keyword line\n0 0 0 255 0 0 0 0\n"
                                               "1 0 0 0.5 0.5 0.5 1 0\n1 1 0 0 0 255 255 1 1\n0 1 0 1 1 1 0 1\n"
                                               "4 0 1 2 3 255 0 0\n3 0 2 1\n"));
  return seeds;
}

}  // namespace slim::fuzz
