// OFF: read and written here (mesh_io.h says why not through VCG).
//
// Read: the "[ST][C][N]OFF" keyword (its counts may follow on the same line), then
// "#V #F #E", then one vertex a line: x y z, [nx ny nz] with N, [colour] with C (3 or 4
// components, integers 0..255 or decimals 0..1; a single colour-map index is ignored), [s t]
// with ST; then one face a line: n i_1 .. i_n [colour]. '#' starts a comment. Polygons become
// fans of triangles from their first corner. 4OFF, nOFF and binary OFF are refused.
// Written: the same keyword for what the source has, each vertex with its normal, colour and
// texture coordinate, each face as a triangle with the run's ramp colour (or the file's own
// face colour when there is no run result).
#include <algorithm>
#include <cerrno>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "mesh_io/mesh_formats.h"
#include "vcg_adapters/quality_ramp.h"

namespace slim::io::detail {
namespace {

class OffLines {
 public:
  OffLines(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}
  // The next line with a token, split; false at the end of the file.
  bool next(std::vector<std::string_view>& tok) {
    tok.clear();
    while (tok.empty() && at_ < bytes_.size()) {
      size_t end = bytes_.find('\n', at_);
      if (end == std::string::npos) end = bytes_.size();
      std::string_view line(bytes_.data() + at_, end - at_);
      at_ = end + 1;
      ++lineno_;
      line = line.substr(0, line.find('#'));
      size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
        if (j > i) tok.push_back(line.substr(i, j - i));
        i = j;
      }
    }
    return !tok.empty();
  }
  double number(std::string_view s) const {
    double x = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      refuse(path_, "'" + std::string(s.substr(0, 40)) + "' is not a number" + where());
    return x;
  }
  std::uint64_t count(std::string_view s) const {
    std::uint64_t n = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), n);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      refuse(path_, "'" + std::string(s.substr(0, 40)) + "' is not a count" + where());
    return n;
  }
  std::string where() const { return " on line " + std::to_string(lineno_); }
  std::uint64_t left() const { return bytes_.size() - std::min(bytes_.size(), at_); }

 private:
  const std::string& path_;
  const std::string& bytes_;
  size_t at_ = 0;
  long lineno_ = 0;
};

// 3 or 4 colour components, integers 0..255 or decimals 0..1 (any '.', 'e' or a value <= 1 in
// a decimal spelling counts as decimal).
Eigen::Matrix<unsigned char, 1, 4> colour(const OffLines& in, const std::vector<std::string_view>& tok, size_t from) {
  bool decimal = false;
  for (size_t k = from; k < tok.size(); ++k) decimal = decimal || tok[k].find_first_of(".eE") != std::string_view::npos;
  Eigen::Matrix<unsigned char, 1, 4> c(255, 255, 255, 255);
  for (size_t k = from; k < tok.size() && k < from + 4; ++k) {
    const double x = in.number(tok[k]) * (decimal ? 255.0 : 1.0);
    c(static_cast<int>(k - from)) = static_cast<unsigned char>(std::clamp(std::isfinite(x) ? std::round(x) : 0.0, 0.0, 255.0));
  }
  return c;
}

}  // namespace

MeshFile read_off(const std::string& path, const std::string& bytes) {
  OffLines in(path, bytes);
  std::vector<std::string_view> tok;
  if (!in.next(tok)) refuse(path, "the file is empty");
  const std::string_view key = tok[0];
  const size_t off = key.rfind("OFF");
  if (off == std::string_view::npos || off + 3 != key.size()) refuse(path, "not an OFF file (no OFF keyword)");
  const std::string_view prefix = key.substr(0, off);
  const bool has_texcoord = prefix.find("ST") != std::string_view::npos;
  const bool has_colour = prefix.find('C') != std::string_view::npos, has_normal = prefix.find('N') != std::string_view::npos;
  if (prefix.find_first_of("4n") != std::string_view::npos) refuse(path, "4OFF and nOFF (not three-dimensional) are not supported");
  if (tok.size() > 1 && tok[1] == "BINARY") refuse(path, "binary OFF is not supported (write it as ASCII OFF, or PLY)");
  if (tok.size() > 1) {
    tok.erase(tok.begin());  // the counts follow the keyword on its line
  } else if (!in.next(tok)) {
    refuse(path, "no vertex and face counts");
  }
  if (tok.size() < 2) refuse(path, "no vertex and face counts" + in.where());
  const std::uint64_t nv = in.count(tok[0]), nf = in.count(tok[1]);
  // Refused before anything is allocated: a vertex line takes at least 6 bytes ("0 0 0\n"), a
  // face line at least 8 ("3 0 1 2\n").
  check_count(path, "vertices", nv, 6, in.left());
  check_count(path, "faces", nf, 8, in.left() - 6 * nv);

  MeshFile file;
  file.format = MeshFormat::Off;
  Surface& s = file.surface;
  s.V.resize(static_cast<Eigen::Index>(nv), 3);
  if (has_normal) file.vertex.normal.resize(s.V.rows(), 3);
  if (has_colour) file.vertex.colour.resize(s.V.rows(), 4);
  if (has_texcoord) file.vertex.texcoord.resize(s.V.rows(), 2);
  const size_t fixed = 3 + (has_normal ? 3 : 0), tail = has_texcoord ? 2 : 0;
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) {
    if (!in.next(tok)) refuse(path, "the file ends after " + std::to_string(i) + " of its " + std::to_string(nv) + " vertices");
    if (tok.size() < fixed + tail) refuse(path, "vertex " + std::to_string(i) + " has too few numbers" + in.where());
    for (int k = 0; k < 3; ++k) s.V(i, k) = in.number(tok[static_cast<size_t>(k)]);
    if (has_normal)
      for (int k = 0; k < 3; ++k) file.vertex.normal(i, k) = in.number(tok[static_cast<size_t>(3 + k)]);
    if (has_colour) {
      const size_t n = tok.size() - fixed - tail;
      if (n != 0 && n != 1 && n != 3 && n != 4) refuse(path, "vertex " + std::to_string(i) + " has a colour of " + std::to_string(n) + " numbers" + in.where());
      std::vector<std::string_view> c(tok.begin() + static_cast<long>(fixed), tok.end() - static_cast<long>(tail));
      file.vertex.colour.row(i) = n >= 3 ? colour(in, c, 0) : Eigen::Matrix<unsigned char, 1, 4>(255, 255, 255, 255);
    }
    if (has_texcoord)
      for (int k = 0; k < 2; ++k) file.vertex.texcoord(i, k) = in.number(tok[tok.size() - 2 + static_cast<size_t>(k)]);
  }
  std::vector<Eigen::Vector3i> tris;
  std::vector<Eigen::Matrix<unsigned char, 1, 4>> face_colour;
  bool any_colour = false;
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!in.next(tok)) refuse(path, "the file ends after " + std::to_string(f) + " of its " + std::to_string(nf) + " faces");
    const std::uint64_t n = in.count(tok[0]);
    const std::string face = "face " + std::to_string(f);
    if (n < 3) refuse(path, face + " has " + std::to_string(n) + " corners (a face needs 3 or more)" + in.where());
    if (n > tok.size() - 1) refuse(path, face + " lists fewer corners than its count " + std::to_string(n) + in.where());
    std::vector<int> corner(n);
    for (size_t k = 0; k < n; ++k) {
      const std::uint64_t c = in.count(tok[k + 1]);
      if (c >= nv) refuse(path, face + " names vertex " + std::string(tok[k + 1]) + ", but there are " + std::to_string(nv) + " vertices" + in.where());
      corner[k] = static_cast<int>(c);
    }
    const size_t extra = tok.size() - n - 1;
    const bool coloured = extra >= 3;
    any_colour = any_colour || coloured;
    for (size_t k = 2; k < n; ++k) {
      tris.emplace_back(corner[0], corner[k - 1], corner[k]);
      face_colour.push_back(coloured ? colour(in, tok, n + 1) : Eigen::Matrix<unsigned char, 1, 4>(255, 255, 255, 255));
    }
  }
  s.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i) s.F.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
  if (any_colour) {
    file.face.colour.resize(s.F.rows(), 4);
    for (size_t i = 0; i < tris.size(); ++i) file.face.colour.row(static_cast<Eigen::Index>(i)) = face_colour[i];
  }
  return file;
}

void write_off(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results) {
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out) write_failed(path, "cannot open the file");
  const Points normals = normals_to_write(source, V);
  const VertexAttributes& va = source.vertex;
  const bool colour = va.colour.rows() > 0, texcoord = va.texcoord.rows() > 0;
  const Triangles& F = source.surface.F;
  out << (texcoord ? "ST" : "") << (colour ? "C" : "") << (normals.rows() ? "N" : "") << "OFF\n"
      << V.rows() << " " << F.rows() << " 0\n";
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    out << shortest(V(i, 0)) << " " << shortest(V(i, 1)) << " " << shortest(V(i, 2));
    if (normals.rows()) out << " " << shortest(normals(i, 0)) << " " << shortest(normals(i, 1)) << " " << shortest(normals(i, 2));
    if (colour) out << " " << int(va.colour(i, 0)) << " " << int(va.colour(i, 1)) << " " << int(va.colour(i, 2)) << " " << int(va.colour(i, 3));
    if (texcoord) out << " " << shortest(va.texcoord(i, 0)) << " " << shortest(va.texcoord(i, 1));
    out << "\n";
  }
  const bool ramp = results.quality.size() > 0, own = !ramp && source.face.colour.rows() > 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out << "3 " << F(f, 0) << " " << F(f, 1) << " " << F(f, 2);
    if (ramp || own) {
      const Eigen::Matrix<unsigned char, 1, 4> c = ramp ? vcg_adapters::quality_ramp_colour(results.quality(f)) : Eigen::Matrix<unsigned char, 1, 4>(source.face.colour.row(f));
      out << " " << int(c(0)) << " " << int(c(1)) << " " << int(c(2)) << " " << int(c(3));
    }
    out << "\n";
  }
  out.close();
  if (!out) write_failed(path, "writing failed");
}

}  // namespace slim::io::detail
