// The per-format readers and writers behind mesh_io.h, and what they share. Internal to
// slim_mesh_io: the CLI and the tests use mesh_io.h.
#pragma once

#include <cstdint>
#include <string>

#include "mesh_io/mesh_io.h"

namespace slim::io::detail {

// The selection bit of PLY "flags" properties, as VCG (and so MeshLab) writes it.
constexpr int kSelectedBit = 0x20;

// "cannot read <path>: <why>"
[[noreturn]] void refuse(const std::string& path, const std::string& why);
// "cannot write <path>: <what> (<the system's reason>)", the reason from errno when it has one.
[[noreturn]] void write_failed(const std::string& path, const std::string& what);

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

// The readers parse a file's bytes; `path` names it in messages.
MeshFile read_ply(const std::string& path, const std::string& bytes);
void write_ply(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results);

MeshFile read_obj(const std::string& path, const std::string& bytes);
void write_obj(const std::string& path, const MeshFile& source, const Points& V);

MeshFile read_off(const std::string& path, const std::string& bytes);
void write_off(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results);

// 3MF through lib3mf (threemf_file.cpp).
// The package's bytes with root relationships to missing parts dropped, which lib3mf 1.x would
// refuse (threemf_package.cpp); the bytes as given when there is none or they are not a zip.
std::string readable_3mf_package(const std::string& bytes);
MeshFile read_3mf(const std::string& path, const std::string& bytes);
void write_3mf(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results);

}  // namespace slim::io::detail
