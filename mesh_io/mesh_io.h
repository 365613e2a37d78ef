// Mesh files <-> slim::Surface for the CLI and the tests (PLY, STL, OBJ, OFF, 3MF). The plugin does not
// use this: MeshLab does its own IO. docs/files-and-attributes.md is the user's account of it.
//
// The contract: what goes in comes out.
//   * Indexed formats (PLY, OFF, OBJ): the surface is the file's vertex list and face list, in the
//     file's order. Nothing is welded, removed or reordered: duplicate, coincident and
//     unreferenced vertices stay. (The core sees coincident vertices merged through a view, see
//     core/geometry/welded_view.h; that never reaches the file.) A polygon becomes a fan of triangles from
//     its first corner, in order (OBJ output keeps the polygon itself).
//   * STL stores each triangle's three corners on their own; the reader welds corners with equal
//     coordinates, in order of first appearance, and says how many corners it read.
//   * 3MF (through lib3mf) holds objects placed by a build: the surface is every mesh the build
//     places, in build order, each moved by its item's transform (composed with its components')
//     and scaled from the file's unit to millimetres. ThreeMfBuild remembers each placement, and a
//     3MF written from it gets the same unit, objects, names and transforms back, each object's
//     own vertices moved as its part of the surface moved.
//   * Attributes the file carries come back out on write_mesh (MeshFile holds them): see
//     VertexAttributes / FaceAttributes. Face quality, face colour and face selection are the
//     ones a run replaces (FaceExtras); vertex normals are recomputed when a vertex moved.
//   * Readers refuse, with std::runtime_error("cannot read <path>: <why>"), before anything is
//     allocated for them, counts that the file's size cannot hold, and indices out of range.
//
// Who reads what. PLY, OBJ, STL and OFF are read here, not through VCG 2020.09's importers: its
// PLY reader allocates for a header's counts before reading any data and copies face lists into a
// fixed 512-entry array whatever their count; its OBJ reader drops every face that uses the
// file's first vertex; its STL reader over-reads the 80-byte binary header and dereferences a
// null FILE* for a missing file; its OFF reader indexes vertices with unchecked file numbers.
// PLY, OBJ and OFF are written here too: VCG's binary PLY writer declares float texture
// coordinates and writes doubles, and its OBJ writer keeps 6 decimals, which flattens a 1e-3 mm
// part; OBJ and OFF numbers are the shortest decimals that read back to the same double. STL is
// written through VCG's exporter.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim::io {

enum class MeshFormat { Ply, Stl, Obj, Off, ThreeMf };

// The format an extension (.ply, .stl, .obj, .off, .3mf, any case) names; throws std::runtime_error
// naming the path for any other.
MeshFormat format_of(const std::string& path);

using Rgba = Eigen::Matrix<unsigned char, Eigen::Dynamic, 4, Eigen::RowMajor>;

// Per-vertex attributes of a file; each is empty when the file has none, else has #V rows.
struct VertexAttributes {
  Rgba colour;                                       // PLY red/green/blue/alpha, OFF "C", OBJ "v x y z r g b"
  Points normal;                                     // PLY nx/ny/nz, OFF "N"
  Eigen::Matrix<double, Eigen::Dynamic, 2> texcoord; // PLY texture_u/v, OFF "ST"
  Eigen::VectorXd quality;                           // PLY quality
  std::vector<bool> selected;                        // PLY vertex flags (the selection bit)
};

// Per-face attributes of a file; each is empty when the file has none, else has #F rows.
struct FaceAttributes {
  Rgba colour;                                              // PLY, OFF
  Eigen::VectorXd quality;                                  // PLY
  std::vector<bool> selected;                               // PLY face flags (the selection bit)
  Eigen::Matrix<double, Eigen::Dynamic, 6> wedge_texcoord;  // PLY texcoord: (u, v) of corners 0, 1, 2
  Eigen::VectorXi texture;                                  // PLY texnumber: index into MeshFile::textures
};

struct ObjRecords;  // an OBJ file's lines, for writing it back as it was (obj_file.cpp)

// One mesh a 3MF build places: its rows in MeshFile::surface and where it sits. `transform` maps
// the object's own coordinates (file units) to the plate's: [A | a], x -> A x + a, the build
// item's composed with those of the components it went through.
struct ThreeMfPart {
  std::string name;  // the object's name ("" when it has none)
  Eigen::Index first_vertex = 0, vertex_count = 0, first_face = 0, face_count = 0;
  Eigen::Matrix<double, 3, 4> transform = Eigen::Matrix<double, 3, 4>::Identity();
};

// A 3MF file's unit and build; no parts for the other formats.
struct ThreeMfBuild {
  int unit = 1;                        // lib3mf's eModelUnit: 0 micron, 1 mm, 2 cm, 3 inch, 4 foot, 5 metre
  double millimetres_per_unit = 1.0;   // what one file unit is in mm
  std::vector<ThreeMfPart> parts;
};

struct MeshFile {
  MeshFormat format = MeshFormat::Ply;
  Surface surface;
  VertexAttributes vertex;
  FaceAttributes face;
  std::vector<std::string> textures;  // texture file names (PLY "comment TextureFile")
  Eigen::Index stl_corners = 0;       // STL: the corners read (3 per triangle) before welding
  std::shared_ptr<const ObjRecords> obj;  // OBJ: its records (v, vt, vn, f, g, usemtl, ...)
  ThreeMfBuild build;                     // 3MF: its unit and what its build places
};

// Per-face results a run writes, replacing the file's own. Empty means "keep the file's".
struct FaceExtras {
  Eigen::VectorXd quality;     // #F: written as face quality (PLY) and as the ramp colour (PLY, OFF, STL, 3MF)
  std::vector<bool> selected;  // #F: written as the face selection (PLY)
};

// `file` with a run's displacement (#V, mm) as its vertex quality and as vertex colours on the
// displacement ramp, red at `top_mm` (vcg_adapters/displacement_ramp.h), each only where the file
// has none of its own.
MeshFile with_displacement(const MeshFile& file, const Eigen::VectorXd& displacement_mm, double top_mm);

// Reads a mesh file as described above.
MeshFile read_mesh(const std::string& path);
// The same from the file's bytes (`path` gives the format and names the file in messages).
MeshFile parse_mesh(const std::string& path, const std::string& bytes);

// Writes `source` with its vertices at V (#V by 3, source.surface's order) and `results` over the
// file's face quality, colour and selection; the format follows the extension of `path`, and an
// attribute the target format cannot hold is left out. Throws std::runtime_error on failure.
void write_mesh(const std::string& path, const MeshFile& source, const Points& V, const FaceExtras& results = {});

// The surface alone; `extras` (when given) receives the file's face quality and selection.
Surface load_surface(const std::string& path, FaceExtras* extras = nullptr);
// A surface with no attributes of its own, plus `extras`.
void save_surface(const std::string& path, const Surface& s, const FaceExtras& extras = {});

}  // namespace slim::io
