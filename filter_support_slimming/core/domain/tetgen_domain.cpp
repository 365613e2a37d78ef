#include "core/domain/tetgen_domain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry/surface_intersections.h"
#include "core/print/print_setup.h"

#ifdef SLIM_HAVE_TETGEN
#include <signal.h>
#include <tetgen.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>

#include "core/platform/child_process.h"
#endif

namespace slim {

namespace {

void check_orientation_and_closure(const Surface& s) {
  const EdgeTopology edges = edge_topology(s);
  if (edges.open_edges > 0)
    throw std::invalid_argument("the mesh is not closed: " + std::to_string(edges.open_edges) +
                                " edge(s) belong to one face only, e.g. edge " + edges.first_open +
                                "; TetGen needs a closed surface (use the voxel domain)");
  if (edges.nonmanifold_edges > 0)
    throw std::invalid_argument("the mesh is not manifold: " + std::to_string(edges.nonmanifold_edges) +
                                " edge(s), e.g. edge " + edges.first_nonmanifold +
                                "; TetGen needs every edge shared by exactly two faces (use the voxel domain)");
  if (edges.flipped_edges > 0)
    throw std::invalid_argument("the mesh is not consistently oriented: " + edges.first_flipped + " (" +
                                std::to_string(edges.flipped_edges) + " such edge(s))");
}

void check_self_intersections(const Surface& s) {
  int f = 0, g = 0;
  if (first_self_intersection(s, f, g))
    throw std::invalid_argument("the mesh intersects itself: faces " + std::to_string(f) + " and " + std::to_string(g) +
                                " meet where they share no edge; TetGen would crash on it (use the voxel domain)");
}

}  // namespace

void check_tetgen_input(const Surface& s) {
  check_surface(s);
  check_tetgen_input(CheckedSurface(s));
}

void check_tetgen_input(const CheckedSurface& checked) {
  const Surface& s = checked.get();
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces");
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)).transpose(), b = s.V.row(s.F(f, 1)).transpose(),
                          c = s.V.row(s.F(f, 2)).transpose();
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (s.F(f, 0) == s.F(f, 1) || s.F(f, 1) == s.F(f, 2) || s.F(f, 0) == s.F(f, 2) ||
        !((b - a).cross(c - a).norm() > 1e-12 * longest))
      throw std::invalid_argument("face " + std::to_string(f) +
                                  " has zero area (a degenerate triangle); TetGen cannot take it");
  }
  check_orientation_and_closure(s);
  check_self_intersections(s);
}

#ifndef SLIM_HAVE_TETGEN

bool tetgen_available() { return false; }

[[noreturn]] static void not_built() {
  throw std::runtime_error(
      "this build of support-slimming was built without TetGen (SLIM_WITH_TETGEN=OFF or libtet missing): "
      "use the voxel domain");
}

TetgenDomain tetgen_domain(const CheckedSurface&, const Eigen::Vector3d&, const TetgenOptions&) { not_built(); }
TetgenDomain tetgen_domain(const Surface&, const Eigen::Vector3d&, const TetgenOptions&) { not_built(); }

#else

namespace {

// What the child writes before the arrays.
struct ResultHeader {
  std::uint32_t magic;
  std::int32_t status;  // 0 = success, else TetGen's error code (1 = out of memory)
  std::int32_t points, tets, corners;
};
constexpr std::uint32_t kMagic = 0x534c494d;  // "SLIM"

// What TetGen's child writes: a header, then on success the points and the tets.
bool tetrahedralize_into(int fd, tetgenbehavior& behaviour, tetgenio& in, const TetgenOptions& o) {
  if (o.test_fault == TetgenChildFault::crash) raise(SIGSEGV);
  if (o.test_fault == TetgenChildFault::hang)
    for (;;) pause();
  ResultHeader h{kMagic, 0, 0, 0, 0};
  tetgenio out;
  try {
    tetrahedralize(&behaviour, &in, &out);
  } catch (int code) {
    h.status = code == 0 ? 2 : code;
  } catch (...) {
    h.status = 1;  // std::bad_alloc under the memory limit
  }
  if (h.status == 0) {
    h.points = out.numberofpoints;
    h.tets = out.numberoftetrahedra;
    h.corners = out.numberofcorners;
  }
  bool ok = write_all(fd, &h, sizeof h);
  if (ok && h.status == 0) {
    ok = write_all(fd, out.pointlist, sizeof(REAL) * 3 * static_cast<size_t>(h.points)) &&
         write_all(fd, out.tetrahedronlist, sizeof(int) * static_cast<size_t>(h.corners) * static_cast<size_t>(h.tets));
  }
  return ok;
}

std::string tetgen_error(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 3: return "TetGen found a self-intersection in the surface";
    case 4: return "TetGen found a very small input feature (nearly touching faces)";
    case 5: return "TetGen found two very close input facets";
    case 10: return "TetGen found an input error";
    default: return "TetGen failed with an internal error (code " + std::to_string(code) + ")";
  }
}

// TetGen's input: the referenced vertices (their domain numbers in surface_vertex, -1 for the
// others) and one facet per face. Prepared here, so the child allocates as little as possible.
void fill_tetgen_input(const Surface& surface, tetgenio& in, Eigen::VectorXi& surface_vertex, std::vector<int>& input_vertex) {
  surface_vertex = Eigen::VectorXi::Constant(surface.V.rows(), -1);
  for (Eigen::Index v : face_vertices(surface)) {
    surface_vertex(v) = static_cast<int>(input_vertex.size());
    input_vertex.push_back(static_cast<int>(v));
  }
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(input_vertex.size());
  in.pointlist = new REAL[3 * input_vertex.size()];
  for (size_t i = 0; i < input_vertex.size(); ++i)
    for (int a = 0; a < 3; ++a) in.pointlist[3 * i + static_cast<size_t>(a)] = surface.V(input_vertex[i], a);
  in.numberoffacets = static_cast<int>(surface.F.rows());
  in.facetlist = new tetgenio::facet[static_cast<size_t>(surface.F.rows())];
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) facet.polygonlist[0].vertexlist[k] = surface_vertex(surface.F(f, k));
  }
}

// The child's bytes -> the domain's mesh, checked: complete, the input points first and
// unchanged, every tet positive (flipped where TetGen's orientation is the other one).
void read_tetgen_result(const std::vector<char>& data, const Surface& surface, const std::vector<int>& input_vertex,
                        TetMesh& mesh) {
  ResultHeader h{};
  if (data.size() < sizeof h) throw std::runtime_error("TetGen's process returned no result");
  std::memcpy(&h, data.data(), sizeof h);
  if (h.magic != kMagic) throw std::runtime_error("TetGen's process returned garbage");
  if (h.status != 0) throw std::runtime_error(tetgen_error(h.status) + "; use the voxel domain");
  const size_t point_bytes = sizeof(REAL) * 3 * static_cast<size_t>(h.points);
  const size_t tet_bytes = sizeof(int) * static_cast<size_t>(h.corners) * static_cast<size_t>(h.tets);
  if (h.points < static_cast<int>(input_vertex.size()) || h.tets <= 0 || h.corners < 4 ||
      data.size() != sizeof h + point_bytes + tet_bytes)
    throw std::runtime_error("TetGen's process returned an incomplete result");
  // Copied out, not cast: the points start right after the 20-byte header, so a REAL* into the
  // buffer would be misaligned (undefined behaviour; UBSan flagged it).
  std::vector<REAL> P(3 * static_cast<size_t>(h.points));
  std::memcpy(P.data(), data.data() + sizeof h, point_bytes);
  mesh.V.resize(h.points, 3);
  for (Eigen::Index i = 0; i < h.points; ++i)
    for (int a = 0; a < 3; ++a) mesh.V(i, a) = P[static_cast<size_t>(3 * i + a)];
  // With "Y" TetGen keeps the input points first and unchanged; the embedding relies on it.
  for (size_t i = 0; i < input_vertex.size(); ++i)
    if (mesh.V.row(static_cast<Eigen::Index>(i)) != surface.V.row(input_vertex[i]))
      throw std::runtime_error("TetGen moved or renumbered the surface vertices (do not drop \"Y\")");
  std::vector<int> T(static_cast<size_t>(h.corners) * static_cast<size_t>(h.tets));
  std::memcpy(T.data(), data.data() + sizeof h + point_bytes, tet_bytes);
  mesh.T.resize(h.tets, 4);
  for (Eigen::Index t = 0; t < h.tets; ++t) {
    for (int c = 0; c < 4; ++c) {
      const int v = T[static_cast<size_t>(t * h.corners + c)];
      if (v < 0 || v >= h.points) throw std::runtime_error("TetGen's result refers to a vertex it does not have");
      mesh.T(t, c) = v;
    }
    const double vol = tet_volume(mesh.V, mesh.T.row(t));
    if (vol == 0.0) throw std::runtime_error("TetGen produced a flat tet");
    if (vol < 0.0) std::swap(mesh.T(t, 2), mesh.T(t, 3));
  }
}

}  // namespace

bool tetgen_available() { return true; }

TetgenDomain tetgen_domain(const Surface& surface, const Eigen::Vector3d& print_direction, const TetgenOptions& o) {
  const Eigen::Vector3d d = unit_print_direction(print_direction);
  if (!(o.timeout_seconds > 0)) throw std::invalid_argument("the TetGen timeout must be positive");
  if (!(o.max_tet_volume >= 0)) throw std::invalid_argument("the maximum tet volume must be >= 0");
  return tetgen_domain(CheckedSurface(surface), d, o);
}

TetgenDomain tetgen_domain(const CheckedSurface& checked, const Eigen::Vector3d& print_direction, const TetgenOptions& o) {
  const Eigen::Vector3d d = unit_print_direction(print_direction);
  if (!(o.timeout_seconds > 0)) throw std::invalid_argument("the TetGen timeout must be positive");
  if (!(o.max_tet_volume >= 0)) throw std::invalid_argument("the maximum tet volume must be >= 0");
  check_tetgen_input(checked);
  const Surface& surface = checked.get();
  TetgenDomain dom;
  tetgenio in;
  std::vector<int> input_vertex;
  fill_tetgen_input(surface, in, dom.surface_vertex, input_vertex);
  std::string switches = o.switches + "zQ";
  if (o.max_tet_volume > 0) switches += "a" + std::to_string(o.max_tet_volume);
  tetgenbehavior behaviour;
  if (!behaviour.parse_commandline(switches.data()))
    throw std::invalid_argument("TetGen does not accept the switches \"" + o.switches + "\"");

  ChildProcessOptions child;
  child.name = "TetGen";
  child.advice = "use the voxel domain";
  child.timeout_seconds = o.timeout_seconds;
  child.memory_bytes = o.child_memory_bytes;
  read_tetgen_result(run_in_child([&](int fd) { return tetrahedralize_into(fd, behaviour, in, o); }, child), surface,
                     input_vertex, dom.mesh);
  const Eigen::VectorXd height = dom.mesh.V * d;
  dom.plate_height = height.minCoeff();
  const double diag = bbox_diagonal(dom.mesh.V);
  dom.on_plate = height.array() <= dom.plate_height + 1e-9 * diag;
  return dom;
}

#endif

}  // namespace slim
