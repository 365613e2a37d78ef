// OBJ: read and written here (mesh_io.h says why not through VCG).
//
// Read: "v x y z [r g b]" (the common colour extension, in [0, 1]), "vt u v", "vn x y z" and
// "f" records whose corners are "v", "v/t", "v//n" or "v/t/n", 1-based or negative (relative);
// polygons become fans of triangles from their first corner. Every line, these and the others
// (mtllib, usemtl, g, o, s, l, comments), is kept in order.
// Written back from an OBJ: the same lines, with each "v" record's coordinates replaced and
// whatever followed them (a colour) kept. When a vertex moved, the file's normals no longer fit:
// its "vn" records are replaced by one recomputed normal per vertex (where the first "vn" was)
// and every corner's normal index by its vertex's. Written from another format: v (with colour
// when the source has vertex colours), vt (per corner, or per vertex), vn and f records.
// OBJ has no face quality, colour or selection: a run's per-face results are not written.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "mesh_io/mesh_formats.h"

namespace slim::io {

struct ObjRecords {
  struct Corner {
    int v = -1, t = -1, n = -1;  // 0-based; -1 when absent
  };
  enum class Kind { Other, Vertex, Normal, Face };
  std::vector<std::string> lines;   // as read, without the line end
  std::vector<Kind> kinds;          // per line
  std::vector<std::string> vertex_tail;          // per "v": what followed x y z, verbatim
  std::vector<std::vector<Corner>> faces;        // per "f" line, in order
  std::vector<Eigen::Vector2d> texcoords;        // per "vt"
};

namespace detail {
namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

bool parse(std::string_view s, double& x) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// An OBJ index (1-based, or negative counting back from the last one so far) -> 0-based.
int index(const std::string& path, std::string_view token, long count, const char* what, long lineno) {
  long long i = 0;
  const auto r = std::from_chars(token.data(), token.data() + token.size(), i);
  const std::string where = " on line " + std::to_string(lineno);
  if (r.ec != std::errc() || r.ptr != token.data() + token.size())
    refuse(path, "bad " + std::string(what) + " index '" + std::string(token) + "'" + where);
  const long long zero_based = i < 0 ? count + i : i - 1;
  if (i == 0 || zero_based < 0 || zero_based >= count)
    refuse(path, std::string(what) + " index " + std::string(token) + " out of range (" + std::to_string(count) +
                     " so far)" + where);
  return static_cast<int>(zero_based);
}

// What read_obj gathers line by line: the records written back, and the surface's lists.
struct ObjReading {
  explicit ObjReading(const std::string& file) : path(file) {}
  const std::string& path;
  std::shared_ptr<ObjRecords> records = std::make_shared<ObjRecords>();
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> tris;
  std::vector<Eigen::Matrix<double, 1, 6>> wedge;
  std::vector<Eigen::Matrix<unsigned char, 1, 4>> colour;
  bool every_vertex_coloured = true, every_corner_textured = true;
  long normals = 0;

  // "v x y z [r g b]": the position, the rest of the line as written, and the colour if any.
  void vertex(const std::vector<std::string_view>& tok, const std::string& line, const std::string& where) {
    Eigen::Vector3d p;
    if (tok.size() < 4 || !parse(tok[1], p.x()) || !parse(tok[2], p.y()) || !parse(tok[3], p.z()))
      refuse(path, "bad vertex" + where);
    v.push_back(p);
    const size_t tail = static_cast<size_t>(tok[3].data() + tok[3].size() - line.data());
    records->vertex_tail.push_back(line.substr(tail));
    double rgb[3];
    if (tok.size() >= 7 && parse(tok[4], rgb[0]) && parse(tok[5], rgb[1]) && parse(tok[6], rgb[2])) {
      Eigen::Matrix<unsigned char, 1, 4> c;
      for (int k = 0; k < 3; ++k) c(k) = static_cast<unsigned char>(std::lround(std::fmin(std::fmax(rgb[k], 0.0), 1.0) * 255.0));
      c(3) = 255;
      colour.push_back(c);
    } else {
      every_vertex_coloured = false;
    }
  }

  // "f v[/t[/n]] ...": the polygon's corners, and its fan of triangles from the first corner.
  void face(const std::vector<std::string_view>& tok, long lineno, const std::string& where) {
    std::vector<ObjRecords::Corner> poly;
    for (size_t k = 1; k < tok.size(); ++k) {
      const std::string_view c = tok[k];
      const size_t s1 = c.find('/'), s2 = s1 == std::string_view::npos ? s1 : c.find('/', s1 + 1);
      ObjRecords::Corner corner;
      corner.v = index(path, c.substr(0, s1), static_cast<long>(v.size()), "vertex", lineno);
      if (s1 != std::string_view::npos) {
        const std::string_view t = c.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
        if (!t.empty()) corner.t = index(path, t, static_cast<long>(records->texcoords.size()), "texture coordinate", lineno);
        if (s2 != std::string_view::npos) corner.n = index(path, c.substr(s2 + 1), normals, "normal", lineno);
      }
      poly.push_back(corner);
    }
    if (poly.size() < 3) refuse(path, "a face with " + std::to_string(poly.size()) + " corners" + where);
    for (size_t k = 2; k < poly.size(); ++k) {
      const ObjRecords::Corner* c[3] = {&poly[0], &poly[k - 1], &poly[k]};
      tris.emplace_back(c[0]->v, c[1]->v, c[2]->v);
      Eigen::Matrix<double, 1, 6> w = Eigen::Matrix<double, 1, 6>::Zero();
      for (int j = 0; j < 3; ++j) {
        if (c[j]->t < 0) every_corner_textured = false;
        else w.segment<2>(2 * j) = records->texcoords[static_cast<size_t>(c[j]->t)].transpose();
      }
      wedge.push_back(w);
    }
    records->faces.push_back(std::move(poly));
  }

  // One line; what kind of record it is goes with it into the records.
  void line(std::string line, long lineno) {
    const std::vector<std::string_view> tok = split(line);
    ObjRecords::Kind kind = ObjRecords::Kind::Other;
    const std::string where = " on line " + std::to_string(lineno);
    if (!tok.empty() && tok[0] == "v") {
      kind = ObjRecords::Kind::Vertex;
      vertex(tok, line, where);
    } else if (!tok.empty() && tok[0] == "vt") {
      Eigen::Vector2d t(0, 0);
      if (tok.size() < 2 || !parse(tok[1], t.x()) || (tok.size() > 2 && !parse(tok[2], t.y())))
        refuse(path, "bad texture coordinate" + where);
      records->texcoords.push_back(t);
    } else if (!tok.empty() && tok[0] == "vn") {
      kind = ObjRecords::Kind::Normal;
      ++normals;
    } else if (!tok.empty() && tok[0] == "f") {
      kind = ObjRecords::Kind::Face;
      face(tok, lineno, where);
    }
    records->lines.push_back(std::move(line));
    records->kinds.push_back(kind);
  }

  MeshFile file() {
    MeshFile file;
    file.format = MeshFormat::Obj;
    file.surface.V.resize(static_cast<Eigen::Index>(v.size()), 3);
    for (size_t i = 0; i < v.size(); ++i) file.surface.V.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
    file.surface.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
    for (size_t i = 0; i < tris.size(); ++i) file.surface.F.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
    if (every_vertex_coloured && !v.empty()) {
      file.vertex.colour.resize(static_cast<Eigen::Index>(v.size()), 4);
      for (size_t i = 0; i < v.size(); ++i) file.vertex.colour.row(static_cast<Eigen::Index>(i)) = colour[i];
    }
    if (every_corner_textured && !tris.empty()) {
      file.face.wedge_texcoord.resize(static_cast<Eigen::Index>(tris.size()), 6);
      file.face.texture = Eigen::VectorXi::Zero(static_cast<Eigen::Index>(tris.size()));
      for (size_t i = 0; i < tris.size(); ++i) file.face.wedge_texcoord.row(static_cast<Eigen::Index>(i)) = wedge[i];
    }
    file.obj = std::move(records);
    return file;
  }
};

}  // namespace

MeshFile read_obj(const std::string& path, const std::string& bytes) {
  ObjReading reading(path);
  size_t at = 0;
  for (long lineno = 1; at < bytes.size(); ++lineno) {
    size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    std::string line = bytes.substr(at, end - at);
    at = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    reading.line(std::move(line), lineno);
  }
  return reading.file();
}

namespace {

std::string xyz(const Eigen::RowVector3d& p) { return shortest(p(0)) + " " + shortest(p(1)) + " " + shortest(p(2)); }

// The source's own lines, with the new positions (and, when a vertex moved, new normals).
void write_records(std::ofstream& out, const ObjRecords& r, const Points& source_V, const Points& V, const Points& normals,
                   bool renormal) {
  Eigen::Index vertex = 0;
  size_t face = 0;
  bool normals_written = false;
  for (size_t i = 0; i < r.lines.size(); ++i) {
    switch (r.kinds[i]) {
      case ObjRecords::Kind::Vertex:
        if (V.row(vertex) == source_V.row(vertex)) out << r.lines[i] << "\n";  // as it was, digit for digit
        else out << "v " << xyz(V.row(vertex)) << r.vertex_tail[static_cast<size_t>(vertex)] << "\n";
        ++vertex;
        break;
      case ObjRecords::Kind::Normal:
        if (!renormal) {
          out << r.lines[i] << "\n";
        } else if (!normals_written) {
          for (Eigen::Index k = 0; k < normals.rows(); ++k) out << "vn " << xyz(normals.row(k)) << "\n";
          normals_written = true;
        }
        break;
      case ObjRecords::Kind::Face:
        if (!renormal) {
          out << r.lines[i] << "\n";
        } else {
          out << "f";
          for (const ObjRecords::Corner& c : r.faces[face]) {
            out << " " << c.v + 1;
            if (c.t >= 0 || c.n >= 0) out << "/" << (c.t >= 0 ? std::to_string(c.t + 1) : "");
            if (c.n >= 0) out << "/" << c.v + 1;
          }
          out << "\n";
        }
        ++face;
        break;
      case ObjRecords::Kind::Other:
        out << r.lines[i] << "\n";
    }
  }
}

// A source of another format: its vertices, texture coordinates, normals and faces.
void write_plain(std::ofstream& out, const MeshFile& source, const Points& V, const Points& normals) {
  const VertexAttributes& va = source.vertex;
  const Triangles& F = source.surface.F;
  out << "# written by support-slim: " << V.rows() << " vertices, " << F.rows() << " faces\n";
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    out << "v " << xyz(V.row(i));
    if (va.colour.rows())
      for (int k = 0; k < 3; ++k) out << " " << shortest(va.colour(i, k) / 255.0);
    out << "\n";
  }
  for (Eigen::Index i = 0; i < normals.rows(); ++i) out << "vn " << xyz(normals.row(i)) << "\n";
  const bool wedge = source.face.wedge_texcoord.rows() > 0, per_vertex = !wedge && va.texcoord.rows() > 0;
  if (wedge)
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k)
        out << "vt " << shortest(source.face.wedge_texcoord(f, 2 * k)) << " " << shortest(source.face.wedge_texcoord(f, 2 * k + 1)) << "\n";
  if (per_vertex)
    for (Eigen::Index i = 0; i < V.rows(); ++i) out << "vt " << shortest(va.texcoord(i, 0)) << " " << shortest(va.texcoord(i, 1)) << "\n";
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out << "f";
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k) + 1;
      out << " " << v;
      if (wedge || per_vertex || normals.rows()) out << "/";
      if (wedge) out << 3 * f + k + 1;
      if (per_vertex) out << v;
      if (normals.rows()) out << "/" << v;
    }
    out << "\n";
  }
}

}  // namespace

void write_obj(const std::string& path, const MeshFile& source, const Points& V) {
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out) write_failed(path, "cannot open the file");
  const bool moved = V != source.surface.V;
  if (source.obj) {
    const bool has_normals = std::find(source.obj->kinds.begin(), source.obj->kinds.end(), ObjRecords::Kind::Normal) !=
                             source.obj->kinds.end();
    const bool renormal = moved && has_normals;
    write_records(out, *source.obj, source.surface.V, V, renormal ? vertex_normals(V, source.surface.F) : Points(0, 3), renormal);
  } else {
    write_plain(out, source, V, normals_to_write(source, V));
  }
  out.close();
  if (!out) write_failed(path, "writing failed");
}

}  // namespace detail
}  // namespace slim::io
