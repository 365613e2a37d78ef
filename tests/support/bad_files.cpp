// The file-level bad-input catalogue (bad_inputs.h: BadFile): one small tetrahedron, spoiled in
// each way a file from the internet can be, in every format the CLI reads.
#include <cstdint>
#include <cstring>
#include <sstream>

#include "support/bad_inputs.h"

namespace slim::test {
namespace {

const char* const kTetraVertices = "0 0 0\n10 0 0\n0 10 0\n0 0 10\n";
const char* const kTetraFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string ply_header(const std::string& format, const std::string& vertices, const std::string& faces,
                       const std::string& face_list = "uchar int") {
  return "ply\nformat " + format + " 1.0\nelement vertex " + vertices +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces + "\nproperty list " +
         face_list + " vertex_indices\nend_header\n";
}

template <class T>
void put(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

std::string binary_tetra_ply() {
  std::string out = ply_header("binary_little_endian", "4", "4");
  const float v[4][3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  for (const auto& p : v)
    for (float x : p) put(out, x);
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& t : f) {
    put(out, std::uint8_t{3});
    for (int i : t) put(out, i);
  }
  return out;
}

std::string binary_tetra_stl(std::uint32_t claimed) {
  std::string out(80, ' ');
  put(out, claimed);
  const float v[4][3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& t : f) {
    for (int k = 0; k < 3; ++k) put(out, 0.0f);  // the facet normal (readers recompute it)
    for (int i : t)
      for (float x : v[i]) put(out, x);
    put(out, std::uint16_t{0});
  }
  return out;
}

const char* const kAsciiStlFacet = "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 10 0\nvertex 10 0 0\n"
                                   "endloop\nendfacet\nendsolid t\n";

}  // namespace

void PrintTo(const BadFile& f, std::ostream* os) { *os << f.name << "." << f.extension << " (" << f.what << ")"; }

std::vector<BadFile> bad_files() {
  const std::string tetra_ply = binary_tetra_ply(), tetra_stl = binary_tetra_stl(4);
  std::vector<BadFile> files = {
      // ---- PLY ------------------------------------------------------------------------------------
      {"ply_two_billion_vertices", "a PLY header claiming 2,000,000,000 vertices over 4 lines of data", "ply",
       ply_header("ascii", "2000000000", "4") + kTetraVertices + kTetraFaces, "claims 2000000000 vertices"},
      {"ply_two_billion_faces_binary", "a binary PLY claiming 2,000,000,000 faces", "ply",
       ply_header("binary_little_endian", "4", "2000000000") + tetra_ply.substr(tetra_ply.find("end_header\n") + 11),
       "claims 2000000000 faces"},
      {"ply_count_beyond_int", "a PLY header claiming 10^19 vertices", "ply",
       ply_header("ascii", "10000000000000000000", "4") + kTetraVertices + kTetraFaces, "more than the 2147483647"},
      {"ply_truncated_binary", "a binary PLY cut off in its face data", "ply", tetra_ply.substr(0, tetra_ply.size() - 9),
       "truncated"},
      {"ply_face_index_out_of_range", "a face naming vertex 7 of 4", "ply",
       ply_header("ascii", "4", "1") + kTetraVertices + "3 0 1 7\n", "names vertex 7"},
      {"ply_negative_face_index", "a face naming vertex -1", "ply",
       ply_header("ascii", "4", "1") + kTetraVertices + "3 0 1 -1\n", "names vertex -1"},
      {"ply_huge_face_list", "a face whose list claims 1,000,000 corners (int count)", "ply",
       ply_header("ascii", "4", "1", "int int") + kTetraVertices + "1000000 0 1 2\n", "does not fit"},
      {"ply_two_corner_face", "a face with two corners", "ply", ply_header("ascii", "4", "1") + kTetraVertices + "2 0 1\n",
       "has 2 corners"},
      {"ply_no_end_header", "a header that never ends", "ply",
       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n", "no end_header"},
      {"ply_garbage_header", "\"ply\" followed by prose", "ply", "ply\nthis is not a header\n", "unexpected 'this'"},
      {"ply_unknown_format", "format binary_middle_endian", "ply",
       ply_header("binary_middle_endian", "4", "4") + kTetraVertices, "unknown PLY format"},
      {"ply_not_a_number", "an ASCII vertex coordinate 'abc'", "ply",
       ply_header("ascii", "4", "4") + "0 0 0\n10 abc 0\n0 10 0\n0 0 10\n" + kTetraFaces, "'abc' is not a number"},
      {"ply_no_coordinates", "vertices without x, y and z", "ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float u\nend_header\n1\n", "no x, y and z"},
      {"ply_not_ply", "a PNG renamed .ply", "ply", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), "not a PLY file"},
      // ---- STL ------------------------------------------------------------------------------------
      {"stl_two_billion_triangles", "a binary STL whose header claims 2,000,000,000 triangles", "stl",
       binary_tetra_stl(2000000000u), "claims 2000000000 triangles"},
      {"stl_truncated", "a binary STL cut 7 bytes short", "stl", tetra_stl.substr(0, tetra_stl.size() - 7), "claims 4 triangles"},
      {"stl_header_only", "the 84-byte header of a 4-triangle STL", "stl", tetra_stl.substr(0, 84), "claims 4 triangles"},
      {"stl_empty", "an empty file", "stl", "", "not an STL file"},
      {"stl_ascii_short_vertex", "an ASCII STL vertex with two numbers", "stl",
       "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
       "a vertex without three numbers"},
      {"stl_ascii_two_corners", "an ASCII STL facet with two vertices", "stl",
       "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n", "not an STL file"},
      // ---- OBJ ------------------------------------------------------------------------------------
      {"obj_index_out_of_range", "a face naming vertex 9 of 3", "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "out of range"},
      {"obj_index_zero", "a face naming vertex 0 (OBJ counts from 1)", "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
       "out of range"},
      {"obj_relative_index_too_far", "a face naming vertex -4 of 3", "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
       "out of range"},
      {"obj_short_vertex", "a vertex with two coordinates", "obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "bad vertex"},
      {"obj_bad_index_token", "a face corner 'a'", "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 3\n", "bad vertex index 'a'"},
      {"obj_two_corner_face", "a face with two corners", "obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "a face with 2 corners"},
      {"obj_texcoord_out_of_range", "a corner naming texture coordinate 5 of 1", "obj",
       "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/5 3/1\n", "texture coordinate index 5 out of range"},
      // ---- OFF ------------------------------------------------------------------------------------
      {"off_two_billion_vertices", "an OFF claiming 2,000,000,000 vertices", "off",
       std::string("OFF\n2000000000 4 0\n") + kTetraVertices + kTetraFaces, "claims 2000000000 vertices"},
      {"off_two_billion_faces", "an OFF claiming 2,000,000,000 faces", "off",
       std::string("OFF\n4 2000000000 0\n") + kTetraVertices + kTetraFaces, "claims 2000000000 faces"},
      {"off_negative_count", "an OFF claiming -5 vertices", "off", std::string("OFF\n-5 4 0\n") + kTetraVertices + kTetraFaces,
       "'-5' is not a count"},
      {"off_face_index_out_of_range", "a face naming vertex 9 of 4", "off",
       std::string("OFF\n4 1 0\n") + kTetraVertices + "3 0 1 9\n", "names vertex 9"},
      {"off_truncated", "an OFF that ends after its vertices", "off",
       std::string("OFF\n4 4 0\n") + kTetraVertices + "3 0 2 1\n3 0 1 3\n" + std::string(40, '#'), "ends after 2 of its 4 faces"},
      {"off_no_keyword", "an OFF without its OFF line", "off", std::string("4 4 0\n") + kTetraVertices + kTetraFaces,
       "no OFF keyword"},
      {"off_binary", "binary OFF", "off", "OFF BINARY\n", "binary OFF is not supported"},
      {"off_huge_corner_count", "a face claiming 2^64 - 1 corners", "off",
       std::string("OFF\n4 1 0\n") + kTetraVertices + "18446744073709551615 0 1 2\n",
       "fewer corners than its count 18446744073709551615"},
      {"off_two_corner_face", "a face with two corners", "off", std::string("OFF\n4 1 0\n") + kTetraVertices + "2 0 1\n",
       "has 2 corners"},
      {"off_four_dimensional", "4OFF (homogeneous coordinates)", "off", std::string("4OFF\n4 4 0\n") + kTetraVertices,
       "not supported"},
      // ---- 3MF and neither -------------------------------------------------------------------------
      {"threemf_not_a_zip", "an ASCII STL named .3mf", "3mf", kAsciiStlFacet, "not a readable 3MF file"},
      {"threemf_empty", "an empty file named .3mf", "3mf", "", "not a readable 3MF file"},
      {"unknown_extension", "an ASCII STL named .xyz", "xyz", kAsciiStlFacet, "unknown mesh format"}};
  return files;
}

}  // namespace slim::test
