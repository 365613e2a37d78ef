// PLY: written here (ply_reader.cpp says why not through VCG).
//
// What is written: binary little-endian PLY with double coordinates, in the property names and
// order MeshLab reads and writes: vertex x y z [nx ny nz] [flags] [red green blue alpha]
// [quality] [texture_u texture_v]; face vertex_indices [flags] [red green blue alpha] [quality]
// [texcoord] [texnumber], each only when the source (or the run) has it.
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mesh_io/mesh_formats.h"
#include "vcg_adapters/quality_ramp.h"

namespace slim::io::detail {
namespace {

template <class T>
void put(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));  // little-endian hosts only (every one this builds for)
  out.append(raw, sizeof(T));
}

void put_rgba(std::string& out, const Rgba& c, Eigen::Index i) {
  for (int k = 0; k < 4; ++k) put(out, c(i, k));
}

}  // namespace

void write_ply(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results) {
  const Triangles& F = source.surface.F;
  const VertexAttributes& va = source.vertex;
  const FaceAttributes& fa = source.face;
  const Points normals = normals_to_write(source, V);
  // A run's results replace the file's face quality, colour and selection.
  const bool ramp = results.quality.size() > 0;
  const Eigen::VectorXd& face_quality = ramp ? results.quality : fa.quality;
  const std::vector<bool>& face_selected = results.selected.empty() ? fa.selected : results.selected;
  const bool face_colour = ramp || fa.colour.rows() > 0, wedge = fa.wedge_texcoord.rows() > 0;
  const bool texnumber = wedge && (source.textures.size() > 1 || (fa.texture.array() != 0).any());

  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment written by support-slim\n";
  for (const std::string& t : source.textures) h << "comment TextureFile " << t << "\n";
  h << "element vertex " << V.rows() << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (normals.rows()) h << "property double nx\nproperty double ny\nproperty double nz\n";
  if (!va.selected.empty()) h << "property int flags\n";
  if (va.colour.rows()) h << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
  if (va.quality.size()) h << "property double quality\n";
  if (va.texcoord.rows()) h << "property float texture_u\nproperty float texture_v\n";
  h << "element face " << F.rows() << "\nproperty list uchar int vertex_indices\n";
  if (!face_selected.empty()) h << "property int flags\n";
  if (face_colour) h << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
  if (face_quality.size()) h << "property double quality\n";
  if (wedge) h << "property list uchar float texcoord\n";
  if (texnumber) h << "property int texnumber\n";
  h << "end_header\n";

  std::string out = h.str();
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) put(out, V(i, k));
    if (normals.rows())
      for (int k = 0; k < 3; ++k) put(out, normals(i, k));
    if (!va.selected.empty()) put(out, std::int32_t{va.selected[static_cast<size_t>(i)] ? kSelectedBit : 0});
    if (va.colour.rows()) put_rgba(out, va.colour, i);
    if (va.quality.size()) put(out, va.quality(i));
    if (va.texcoord.rows())
      for (int k = 0; k < 2; ++k) put(out, static_cast<float>(va.texcoord(i, k)));
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    put(out, std::uint8_t{3});
    for (int k = 0; k < 3; ++k) put(out, std::int32_t{F(f, k)});
    if (!face_selected.empty()) put(out, std::int32_t{face_selected[static_cast<size_t>(f)] ? kSelectedBit : 0});
    if (ramp) {
      const Eigen::Matrix<unsigned char, 1, 4> c = vcg_adapters::quality_ramp_colour(face_quality(f));
      for (int k = 0; k < 4; ++k) put(out, c(k));
    } else if (face_colour) {
      put_rgba(out, fa.colour, f);
    }
    if (face_quality.size()) put(out, face_quality(f));
    if (wedge) {
      put(out, std::uint8_t{6});
      for (int k = 0; k < 6; ++k) put(out, static_cast<float>(fa.wedge_texcoord(f, k)));
    }
    if (texnumber) put(out, std::int32_t{fa.texture(f)});
  }
  errno = 0;
  std::ofstream file(path, std::ios::binary);
  if (!file) write_failed(path, "cannot open the file");
  file.write(out.data(), static_cast<std::streamsize>(out.size()));
  file.close();
  if (!file) write_failed(path, "writing failed");
}

}  // namespace slim::io::detail
