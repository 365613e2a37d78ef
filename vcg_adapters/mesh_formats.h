// The per-format readers and writers behind mesh_io.h, and what they share. Internal to
// slim_vcg_io: the CLI and the tests use mesh_io.h.
#pragma once

#include <cstdint>
#include <string>

#include <vcg/complex/complex.h>

#include "vcg_adapters/mesh_io.h"

namespace slim::vcgx::detail {

// The VCG mesh PLY and STL go through: every attribute MeshFile can carry.
class IoVertex;
class IoFace;
struct IoTypes : vcg::UsedTypes<vcg::Use<IoVertex>::AsVertexType, vcg::Use<IoFace>::AsFaceType> {};
class IoVertex : public vcg::Vertex<IoTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::Qualityd,
                                    vcg::vertex::Color4b, vcg::vertex::TexCoord2f, vcg::vertex::BitFlags> {};
class IoFace : public vcg::Face<IoTypes, vcg::face::VertexRef, vcg::face::Normal3d, vcg::face::Qualityd,
                                vcg::face::Color4b, vcg::face::WedgeTexCoord2f, vcg::face::BitFlags> {};
class IoMesh : public vcg::tri::TriMesh<std::vector<IoVertex>, std::vector<IoFace>> {};

// The selection bit of PLY "flags" properties, as VCG (and so MeshLab) writes it.
constexpr int kSelectedBit = 0x20;

// "cannot read <path>: <why>"
[[noreturn]] void refuse(const std::string& path, const std::string& why);

// Refuses, before anything is allocated, a count the file cannot hold: `count` items of at least
// `min_bytes` bytes each in `available` bytes ("its header claims 2000000000 vertices, but ...").
// Also refuses counts above what an int index holds (2^31 - 1).
void check_count(const std::string& path, const char* what, std::uint64_t count, std::uint64_t min_bytes,
                 std::uint64_t available);

// The shortest decimal that reads back to exactly `x` ("0.1", "-0", "1e-300").
std::string shortest(double x);

// #V by 3 unit vertex normals of the surface at V: the area-weighted sum of the adjacent faces'
// normals (zero for a vertex no face with area uses).
Points vertex_normals(const Points& V, const Triangles& F);

// The normals to write for `source` at V: none when the file had none; the file's own when no
// vertex moved; recomputed otherwise (the file's no longer fit the surface).
Points normals_to_write(const MeshFile& source, const Points& V);

// The colour a face gets from a run's face quality (the fixed ramp of surface_adapter.h).
Eigen::Matrix<unsigned char, 1, 4> ramp_colour(double quality);

// The readers parse a file's bytes; `path` names it in messages.
MeshFile read_ply(const std::string& path, const std::string& bytes);
void write_ply(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results);

MeshFile read_obj(const std::string& path, const std::string& bytes);
void write_obj(const std::string& path, const MeshFile& source, const Points& V);

MeshFile read_off(const std::string& path, const std::string& bytes);
void write_off(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results);

}  // namespace slim::vcgx::detail
