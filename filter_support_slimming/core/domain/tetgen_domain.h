// The TetGen domain: a constrained tetrahedralization of the surface itself, an alternative to
// the voxel domain (voxel_domain.h) for clean closed meshes. TetGen is AGPL-3 and optional at
// build time (SLIM_WITH_TETGEN); without it every function here except check_tetgen_input throws
// std::runtime_error("... built without TetGen ...").
//
// tetgen_domain(surface, d, options) -> TetgenDomain
//   surface  Surface{V #V by 3, F #F by 3}, mm. Must pass check_tetgen_input.
//   d        print direction (any non-zero vector), only used for the plate.
// TetgenDomain
//   mesh            #DV by 3, #DT by 4. The referenced surface vertices come first, in surface
//                   order, then TetGen's interior (Steiner) points. Every tet has positive volume.
//   surface_vertex  #V: the domain vertex of each surface vertex, -1 for unreferenced vertices
//                   (those are not passed to TetGen and cannot be embedded: remove them first).
//   plate_height    min over the domain's vertices of d·v (mm).
//   on_plate        #DV: d·v at most plate_height + 1e-9 x the domain's bounding-box diagonal.
//
// The switches. Default "pq1.414Y": p tetrahedralizes the closed surface, q1.414 bounds the
// radius-edge ratio (well-shaped tets, as the ARAP energy wants), Y keeps the surface triangles
// unsplit, so no Steiner point lands on the surface. "zQ" (zero-based indices, quiet) is always
// added. Use max_tet_volume to make the interior finer.
//
// Safety. TetGen 1.5 segfaults on self-intersecting input, and inside MeshLab that would lose the
// user's work. So (1) check_tetgen_input refuses what TetGen cannot take (surface_intersections.h
// finds the faces that cross), and (2) TetGen runs in a forked child process that writes its
// result into a pipe (child_process.h); a crash, an out-of-memory or a timeout of the child
// becomes a std::runtime_error in the caller, and the caller lives on.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/geometry/checked_surface.h"
#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"

namespace slim {

enum class TetgenChildFault {
  none,
  crash,  // test hook: the child raises SIGSEGV instead of running TetGen
  hang,   // test hook: the child sleeps until it is killed by the timeout
};

struct TetgenOptions {
  std::string switches = "pq1.414Y";  // see above; "zQ" is always added
  double max_tet_volume = 0.0;         // mm³; > 0 adds "a<volume>", 0 = no bound
  double timeout_seconds = 60.0;       // the child is killed after this long
  double child_memory_bytes = 8e9;     // address space the child may add to the host's (0 = no limit)
  TetgenChildFault test_fault = TetgenChildFault::none;
};

struct TetgenDomain {
  TetMesh mesh;
  Eigen::VectorXi surface_vertex;
  double plate_height = 0.0;
  Eigen::Array<bool, Eigen::Dynamic, 1> on_plate;
};

// True when this build can run TetGen.
bool tetgen_available();

// Throws std::invalid_argument naming the first problem TetGen could not take: no faces, bad
// indices or coordinates, a zero-area face, an edge not shared by exactly two faces (open or
// non-manifold), two faces crossing an edge in the same direction (inconsistent orientation),
// or two faces that intersect (touching counts; faces sharing an edge or a vertex may only meet
// there). Runs on a uniform grid of face boxes, so it stays near-linear.
void check_tetgen_input(const Surface& surface);
void check_tetgen_input(const CheckedSurface& surface);  // the same, the surface already checked

// Throws std::invalid_argument (check_tetgen_input, bad options) or std::runtime_error (built
// without TetGen, TetGen refused the input, crashed, ran out of memory or timed out).
TetgenDomain tetgen_domain(const Surface& surface, const Eigen::Vector3d& d, const TetgenOptions& options = {});
TetgenDomain tetgen_domain(const CheckedSurface& surface, const Eigen::Vector3d& d, const TetgenOptions& options = {});

}  // namespace slim
