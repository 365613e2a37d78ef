// PLY: read here (ply_writer.cpp writes it).
//
// Why not VCG's PLY reader: it allocates for the header's counts before reading a byte of data
// (a header claiming 2,000,000,000 vertices ends in std::bad_alloc), and reads an ASCII face list,
// or a binary one with an int count, into a fixed 512-entry array whatever the count says. Nor its
// writer: for a mesh of doubles it declares float texture coordinates and writes doubles.
//
// What is read: ASCII and binary (both endians). Element "vertex": x y z; nx ny nz; red green
// blue [alpha] (uchar, or float in [0, 1]); quality; texture_u texture_v (or s t); flags (the
// selection bit, 0x20, as MeshLab writes it). Element "face": vertex_indices (or vertex_index), a
// list of 3 or more; flags; red green blue [alpha]; quality; texcoord (a list of 2 per corner);
// texnumber. "comment TextureFile <name>" lines name the textures. Every other element and
// property is skipped (read, not kept). Polygons become fans of triangles from their first
// corner, each triangle with the polygon's attributes.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "mesh_io/mesh_formats.h"

namespace slim::io::detail {
namespace {

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

struct Property {
  std::string name;
  int size = 0;           // bytes of the value (binary); 0 for an unknown type
  bool is_float = false;  // float or double
  bool is_signed = false;
  int count_size = 0;  // > 0: a list, whose count has this many bytes
  bool count_signed = false;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::vector<std::string> textures;
  size_t data_start = 0;
};

// Sets size, is_float, is_signed from a PLY type name; false for an unknown one.
bool scalar_type(const std::string& type, int& size, bool& is_float, bool& is_signed) {
  static const std::map<std::string, std::tuple<int, bool, bool>> kTypes = {
      {"char", {1, false, true}},   {"int8", {1, false, true}},    {"uchar", {1, false, false}},
      {"uint8", {1, false, false}}, {"short", {2, false, true}},   {"int16", {2, false, true}},
      {"ushort", {2, false, false}}, {"uint16", {2, false, false}}, {"int", {4, false, true}},
      {"int32", {4, false, true}},  {"uint", {4, false, false}},   {"uint32", {4, false, false}},
      {"float", {4, true, true}},   {"float32", {4, true, true}},  {"double", {8, true, true}},
      {"float64", {8, true, true}}};
  const auto it = kTypes.find(type);
  if (it == kTypes.end()) return false;
  std::tie(size, is_float, is_signed) = it->second;
  return true;
}

// A "property" line: its type (or list count and item types) and name, onto the last element.
void read_property(const std::string& path, std::istringstream& ls, const std::string& where, Header& h) {
  if (h.elements.empty()) refuse(path, "a property before any element" + where);
  Property p;
  std::string type;
  ls >> type;
  if (type == "list") {
    std::string count_type;
    ls >> count_type >> type;
    int size = 0;
    bool is_float = false;
    if (!scalar_type(count_type, size, is_float, p.count_signed) || is_float)
      refuse(path, "bad list count type '" + count_type + "'" + where);
    p.count_size = size;
  }
  if (!scalar_type(type, p.size, p.is_float, p.is_signed)) refuse(path, "unknown property type '" + type + "'" + where);
  ls >> p.name;
  if (p.name.empty()) refuse(path, "a property without a name" + where);
  h.elements.back().properties.push_back(p);
}

// An "element" line: its name and count, declared once.
void read_element(const std::string& path, std::istringstream& ls, const std::string& line, const std::string& where,
                  Header& h) {
  Element e;
  std::string count;
  ls >> e.name >> count;
  const auto r = std::from_chars(count.data(), count.data() + count.size(), e.count);
  if (e.name.empty() || r.ec != std::errc() || r.ptr != count.data() + count.size())
    refuse(path, "bad element line '" + line + "'" + where);
  for (const Element& other : h.elements)
    if (other.name == e.name) refuse(path, "the element '" + e.name + "' is declared twice" + where);
  h.elements.push_back(e);
}

Header read_header(const std::string& path, const std::string& bytes) {
  Header h;
  size_t at = 0;
  auto next_line = [&](std::string& line) {
    if (at >= bytes.size()) refuse(path, "the PLY header has no end_header line");
    size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    at = end + 1;
  };
  std::string line;
  next_line(line);
  if (line != "ply") refuse(path, "not a PLY file (it does not start with \"ply\")");
  bool have_format = false;
  for (long lineno = 2;; ++lineno) {
    next_line(line);
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    const std::string where = " on header line " + std::to_string(lineno);
    if (word == "end_header") break;
    if (word == "comment") {
      std::string key, name;
      if (ls >> key && key == "TextureFile" && ls >> name) h.textures.push_back(name);
    } else if (word == "obj_info" || word.empty()) {
    } else if (word == "format") {
      std::string kind, version;
      ls >> kind >> version;
      if (kind == "ascii") h.encoding = Encoding::Ascii;
      else if (kind == "binary_little_endian") h.encoding = Encoding::BinaryLittle;
      else if (kind == "binary_big_endian") h.encoding = Encoding::BinaryBig;
      else refuse(path, "unknown PLY format '" + kind + "'" + where);
      have_format = true;
    } else if (word == "element") {
      read_element(path, ls, line, where, h);
    } else if (word == "property") {
      read_property(path, ls, where, h);
    } else {
      refuse(path, "unexpected '" + word + "'" + where);
    }
  }
  if (!have_format) refuse(path, "the PLY header has no format line");
  h.data_start = at;
  // Counts the data cannot hold are refused before anything is allocated for them: a binary
  // item takes at least its fixed-size values and list counts, an ASCII one two bytes a value
  // ("0 "), and any item at least one byte.
  std::uint64_t need = 0;
  const std::uint64_t available = bytes.size() - std::min(bytes.size(), at);
  for (const Element& e : h.elements) {
    std::uint64_t each = 0;
    for (const Property& p : e.properties)
      each += h.encoding == Encoding::Ascii ? 2 : static_cast<std::uint64_t>(p.count_size > 0 ? p.count_size : p.size);
    each = std::max<std::uint64_t>(each, 1);
    const std::string what = e.name == "vertex" ? "vertices" : e.name == "face" ? "faces" : "'" + e.name + "' elements";
    check_count(path, what.c_str(), e.count, each, available - std::min(available, need));
    need += e.count * each;
  }
  return h;
}

// Reads values one at a time from the data section, ASCII or binary.
class DataReader {
 public:
  DataReader(const std::string& path, const std::string& bytes, const Header& h)
      : path_(path), bytes_(bytes), at_(h.data_start), encoding_(h.encoding) {}

  double value(int size, bool is_float, bool is_signed) {
    if (encoding_ == Encoding::Ascii) return ascii_value();
    if (at_ + static_cast<size_t>(size) > bytes_.size()) refuse(path_, "the file ends inside its data (truncated)");
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + at_, static_cast<size_t>(size));
    at_ += static_cast<size_t>(size);
    if (encoding_ == Encoding::BinaryBig) std::reverse(raw, raw + size);
    if (is_float) {
      if (size == 4) { float f; std::memcpy(&f, raw, 4); return f; }
      double d; std::memcpy(&d, raw, 8); return d;
    }
    std::uint64_t u = 0;
    for (int k = size - 1; k >= 0; --k) u = (u << 8) | raw[k];
    if (is_signed && (raw[size - 1] & 0x80)) return static_cast<double>(static_cast<std::int64_t>(u | (~std::uint64_t(0) << (8 * size))));
    return static_cast<double>(u);
  }
  // The bytes left, for bounding a list's count before reading it.
  size_t left() const { return bytes_.size() - std::min(bytes_.size(), at_); }
  bool ascii() const { return encoding_ == Encoding::Ascii; }

 private:
  double ascii_value() {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    size_t end = at_;
    while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
    if (end == at_) refuse(path_, "the file ends inside its data (truncated)");
    double v = 0.0;
    const auto r = std::from_chars(bytes_.data() + at_, bytes_.data() + end, v);
    if (r.ec == std::errc::result_out_of_range) v = std::strtod(std::string(bytes_.data() + at_, end - at_).c_str(), nullptr);
    else if (r.ec != std::errc() || r.ptr != bytes_.data() + end)
      refuse(path_, "'" + bytes_.substr(at_, std::min<size_t>(end - at_, 40)) + "' is not a number");
    at_ = end;
    return v;
  }
  const std::string& path_;
  const std::string& bytes_;
  size_t at_;
  Encoding encoding_;
};

// One item's values: a scalar's in values[p][0], a list's in values[p].
using Item = std::vector<std::vector<double>>;

void read_item(DataReader& in, const std::string& path, const Element& e, Item& item) {
  item.resize(e.properties.size());
  for (size_t k = 0; k < e.properties.size(); ++k) {
    const Property& p = e.properties[k];
    std::vector<double>& v = item[k];
    double n = 1;
    if (p.count_size > 0) {
      n = in.value(p.count_size, false, p.count_signed);
      const double most = static_cast<double>(in.left()) / (in.ascii() ? 2.0 : p.size);
      if (!(n >= 0) || n > most || n != std::floor(n))
        refuse(path, "a '" + p.name + "' list of " + shortest(n) + " values in element '" +
                         e.name + "' does not fit the file");
    }
    v.resize(static_cast<size_t>(n));
    for (double& x : v) x = in.value(p.size, p.is_float, p.is_signed);
  }
}

int find(const Element& e, std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (size_t k = 0; k < e.properties.size(); ++k)
      if (e.properties[k].name == name) return static_cast<int>(k);
  return -1;
}

// A file's number as an int flag word or index: clamped to int's range, NaN as 0 (a cast of an
// out-of-range double is undefined).
long long whole(double x) {
  if (!(x == x)) return 0;
  return static_cast<long long>(std::clamp(x, -2147483648.0, 2147483647.0));
}

unsigned char colour_byte(const Property& p, double x) {
  const double v = p.is_float ? x * 255.0 : x;
  return static_cast<unsigned char>(std::clamp(std::isfinite(v) ? std::round(v) : 0.0, 0.0, 255.0));
}

void read_vertices(DataReader& in, const std::string& path, const Element& e, MeshFile& file) {
  const int x = find(e, {"x"}), y = find(e, {"y"}), z = find(e, {"z"});
  if (x < 0 || y < 0 || z < 0) refuse(path, "its vertices have no x, y and z");
  const int nx = find(e, {"nx"}), ny = find(e, {"ny"}), nz = find(e, {"nz"});
  const int r = find(e, {"red", "diffuse_red"}), g = find(e, {"green", "diffuse_green"}), b = find(e, {"blue", "diffuse_blue"});
  const int a = find(e, {"alpha", "diffuse_alpha"}), q = find(e, {"quality"}), flags = find(e, {"flags"});
  const int u = find(e, {"texture_u", "s"}), t = find(e, {"texture_v", "t"});
  const auto n = static_cast<Eigen::Index>(e.count);
  VertexAttributes& va = file.vertex;
  file.surface.V.resize(n, 3);
  if (nx >= 0 && ny >= 0 && nz >= 0) va.normal.resize(n, 3);
  if (r >= 0 && g >= 0 && b >= 0) va.colour.resize(n, 4);
  if (q >= 0) va.quality.resize(n);
  if (u >= 0 && t >= 0) va.texcoord.resize(n, 2);
  if (flags >= 0) va.selected.resize(static_cast<size_t>(n));
  Item item;
  for (Eigen::Index i = 0; i < n; ++i) {
    read_item(in, path, e, item);
    auto one = [&](int k) {
      if (item[static_cast<size_t>(k)].size() != 1) refuse(path, "vertex " + std::to_string(i) + " has a list where a value belongs");
      return item[static_cast<size_t>(k)][0];
    };
    file.surface.V.row(i) << one(x), one(y), one(z);
    if (va.normal.rows()) va.normal.row(i) << one(nx), one(ny), one(nz);
    if (va.colour.rows())
      va.colour.row(i) << colour_byte(e.properties[r], one(r)), colour_byte(e.properties[g], one(g)),
          colour_byte(e.properties[b], one(b)), a >= 0 ? colour_byte(e.properties[a], one(a)) : 255;
    if (va.quality.size()) va.quality(i) = one(q);
    if (va.texcoord.rows()) va.texcoord.row(i) << one(u), one(t);
    if (flags >= 0) va.selected[static_cast<size_t>(i)] = (whole(one(flags)) & kSelectedBit) != 0;
  }
}

void read_faces(DataReader& in, const std::string& path, const Element& e, MeshFile& file) {
  const int vi = find(e, {"vertex_indices", "vertex_index"});
  if (vi < 0 || e.properties[static_cast<size_t>(vi)].count_size == 0) refuse(path, "its faces have no vertex_indices list");
  const int flags = find(e, {"flags"}), q = find(e, {"quality"}), tc = find(e, {"texcoord"}), tn = find(e, {"texnumber"});
  const int r = find(e, {"red"}), g = find(e, {"green"}), b = find(e, {"blue"}), a = find(e, {"alpha"});
  const Eigen::Index nv = file.surface.V.rows();
  std::vector<Eigen::Vector3i> tris;
  std::vector<Eigen::Matrix<unsigned char, 1, 4>> colour;
  std::vector<double> quality;
  std::vector<bool> selected;
  std::vector<Eigen::Matrix<double, 1, 6>> wedge;
  std::vector<int> texture;
  tris.reserve(static_cast<size_t>(e.count));
  Item item;
  for (std::uint64_t f = 0; f < e.count; ++f) {
    read_item(in, path, e, item);
    const std::vector<double>& corners = item[static_cast<size_t>(vi)];
    const std::string face = "face " + std::to_string(f);
    if (corners.size() < 3) refuse(path, face + " has " + std::to_string(corners.size()) + " corners (a face needs 3 or more)");
    for (double c : corners)
      if (!(c >= 0 && c < static_cast<double>(nv)) || c != std::floor(c))
        refuse(path, face + " names vertex " + shortest(c) + ", but there are " + std::to_string(nv) + " vertices");
    auto one = [&](int k, double fallback) {
      return k >= 0 && item[static_cast<size_t>(k)].size() == 1 ? item[static_cast<size_t>(k)][0] : fallback;
    };
    const std::vector<double>* uv = tc >= 0 ? &item[static_cast<size_t>(tc)] : nullptr;
    if (uv && uv->size() != 2 * corners.size())
      refuse(path, face + " has " + std::to_string(uv->size()) + " texture coordinates for " +
                       std::to_string(corners.size()) + " corners");
    for (size_t k = 2; k < corners.size(); ++k) {  // a fan from the first corner
      const size_t c[3] = {0, k - 1, k};
      tris.emplace_back(int(corners[c[0]]), int(corners[c[1]]), int(corners[c[2]]));
      if (r >= 0 && g >= 0 && b >= 0)
        colour.push_back({colour_byte(e.properties[r], one(r, 0)), colour_byte(e.properties[g], one(g, 0)),
                          colour_byte(e.properties[b], one(b, 0)),
                          a >= 0 ? colour_byte(e.properties[a], one(a, 255)) : static_cast<unsigned char>(255)});
      if (q >= 0) quality.push_back(one(q, 0));
      if (flags >= 0) selected.push_back((whole(one(flags, 0)) & kSelectedBit) != 0);
      if (uv) {
        Eigen::Matrix<double, 1, 6> w;
        for (int j = 0; j < 3; ++j) w.segment<2>(2 * j) << (*uv)[2 * c[j]], (*uv)[2 * c[j] + 1];
        wedge.push_back(w);
        texture.push_back(static_cast<int>(whole(one(tn, 0))));
      }
    }
  }
  const auto nf = static_cast<Eigen::Index>(tris.size());
  file.surface.F.resize(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f) file.surface.F.row(f) = tris[static_cast<size_t>(f)].transpose();
  FaceAttributes& fa = file.face;
  if (!colour.empty()) {
    fa.colour.resize(nf, 4);
    for (Eigen::Index f = 0; f < nf; ++f) fa.colour.row(f) = colour[static_cast<size_t>(f)];
  }
  if (!quality.empty()) fa.quality = Eigen::Map<const Eigen::VectorXd>(quality.data(), nf);
  fa.selected = std::move(selected);
  if (!wedge.empty()) {
    fa.wedge_texcoord.resize(nf, 6);
    fa.texture.resize(nf);
    for (Eigen::Index f = 0; f < nf; ++f) {
      fa.wedge_texcoord.row(f) = wedge[static_cast<size_t>(f)];
      fa.texture(f) = texture[static_cast<size_t>(f)];
    }
  }
}

}  // namespace

MeshFile read_ply(const std::string& path, const std::string& bytes) {
  const Header h = read_header(path, bytes);
  MeshFile file;
  file.format = MeshFormat::Ply;
  file.textures = h.textures;
  file.surface.V.resize(0, 3);
  file.surface.F.resize(0, 3);
  DataReader in(path, bytes, h);
  Item skipped;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") read_vertices(in, path, e, file);
    else if (e.name == "face") read_faces(in, path, e, file);
    else
      for (std::uint64_t i = 0; i < e.count; ++i) read_item(in, path, e, skipped);
  }
  return file;
}

}  // namespace slim::io::detail
