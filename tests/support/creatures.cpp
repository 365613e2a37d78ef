#include "support/creatures.h"

#ifdef SLIM_TESTS_HAVE_VCG

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <type_traits>

// VCG's walker reads a slice cache that -Wmaybe-uninitialized cannot follow once it is inlined
// here (the value is always set before it is read).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/clean.h>
#include <vcg/complex/algorithms/create/marching_cubes.h>
#include <vcg/complex/algorithms/create/mc_trivial_walker.h>

namespace slim::test {
namespace {

class McVertex;
class McFace;
struct McTypes : vcg::UsedTypes<vcg::Use<McVertex>::AsVertexType, vcg::Use<McFace>::AsFaceType> {};
class McVertex : public vcg::Vertex<McTypes, vcg::vertex::Coord3f, vcg::vertex::BitFlags> {};
class McFace : public vcg::Face<McTypes, vcg::face::VertexRef, vcg::face::BitFlags> {};
class McMesh : public vcg::tri::TriMesh<std::vector<McVertex>, std::vector<McFace>> {};

using Volume = vcg::SimpleVolume<vcg::SimpleVoxel<float>>;
// A slice cache of VCG's TrivialWalker: a raw array in MeshLab 2020.09's VCG, which allocates it
// in SetExtractionBox (which BuildMesh calls) and never frees it; a std::vector, which frees
// itself, in 2022.02's and later.
template <class Cache>
void free_slice_cache(Cache& cache) {
  if constexpr (std::is_pointer_v<Cache>) {
    delete[] cache;
    cache = nullptr;
  }
}

class Walker : public vcg::tri::TrivialWalker<McMesh, Volume> {
 public:
  ~Walker() {
    if (_slice_dimension == 0) return;  // never allocated
    free_slice_cache(_x_cs);
    free_slice_cache(_y_cs);
    free_slice_cache(_z_cs);
    free_slice_cache(_x_ns);
    free_slice_cache(_z_ns);
  }
};
using Cubes = vcg::tri::MarchingCubes<McMesh, Walker>;
using Field = std::function<double(const Eigen::Vector3d&)>;  // < 0 inside, about a distance in mm

// Distance-like field of an ellipsoid (exact on a sphere, within the ratio of its radii elsewhere).
double ellipsoid(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii) {
  const Eigen::Vector3d q = (p - centre).cwiseQuotient(radii);
  return (q.norm() - 1.0) * radii.minCoeff();
}

// Exact distance to a capsule (segment a-b of radius r).
double capsule(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - r;
}

// Polynomial smooth minimum: the union of two fields, blended over a width of k mm.
double smooth_union(double a, double b, double k) {
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}

struct Part {
  std::function<double(const Eigen::Vector3d&)> field;
};

// The union of the parts, blended by `blend` mm, cut flat by the plate z = 0.
Field body_plan(std::vector<Part> parts, double blend) {
  return [parts = std::move(parts), blend](const Eigen::Vector3d& p) {
    double f = parts[0].field(p);
    for (size_t i = 1; i < parts.size(); ++i) f = smooth_union(f, parts[i].field(p), blend);
    return std::max(f, -p.z());
  };
}

Part ell(Eigen::Vector3d c, Eigen::Vector3d r) {
  return {[c, r](const Eigen::Vector3d& p) { return ellipsoid(p, c, r); }};
}
Part cap(Eigen::Vector3d a, Eigen::Vector3d b, double r) {
  return {[a, b, r](const Eigen::Vector3d& p) { return capsule(p, a, b, r); }};
}

Field quadruped() {
  std::vector<Part> parts = {ell({0, 0, 22}, {18, 9, 8.5})};
  for (double x : {-11.0, 11.0})
    for (double y : {-5.0, 5.0}) parts.push_back(cap({x, y, 20}, {x * 1.05, y * 1.1, -1}, 3.2));
  parts.push_back(cap({13, 0, 25}, {21, 0, 37}, 4.5));      // neck
  parts.push_back(ell({24, 0, 40}, {7.5, 5.5, 5.5}));       // head
  parts.push_back(ell({31, 0, 38.5}, {4.5, 3.2, 2.8}));     // snout
  parts.push_back(cap({-17, 0, 25}, {-26, 0, 31}, 2.0));    // tail
  return body_plan(std::move(parts), 3.0);
}

Field long_neck() {
  std::vector<Part> parts = {ell({0, 0, 17}, {20, 11, 10.5})};
  for (double x : {-12.0, 12.0})
    for (double y : {-6.5, 6.5}) parts.push_back(cap({x, y, 14}, {x, y * 1.1, -1}, 4.5));
  parts.push_back(cap({16, 0, 20}, {27, 0, 42}, 4.0));      // neck
  parts.push_back(ell({31, 0, 45}, {6.5, 4.0, 4.0}));       // head
  parts.push_back(cap({-18, 0, 16}, {-34, 0, 9}, 3.5));     // tail
  return body_plan(std::move(parts), 3.5);
}

Field upright() {
  std::vector<Part> parts = {ell({0, 0, 22}, {11, 10, 16})};
  for (double y : {-5.0, 5.0}) parts.push_back(cap({1, y, 8}, {2, y, -1}, 3.0));  // legs
  for (double y : {-5.0, 5.0}) parts.push_back(ell({5, y, 1.5}, {5, 2.5, 1.5}));  // feet
  parts.push_back(ell({0, 0, 44}, {8, 7.5, 7.5}));          // head
  parts.push_back(ell({9, 0, 42}, {5, 2.2, 1.8}));          // beak, its underside a chin
  for (double y : {-11.0, 11.0}) parts.push_back(ell({-1, y, 25}, {4.5, 1.8, 10}));  // flippers
  return body_plan(std::move(parts), 2.5);
}

// Marching cubes over the box [lo, hi] at spacing `cell`, with empty layers of padding around it
// (VCG's walker leaves the last two layers of the grid out). The samples sit half a cell off the
// plate z = 0, so none lies exactly on the level set there.
Surface mesh_level_set(const Field& f, const Eigen::Vector3d& lo_in, const Eigen::Vector3d& hi_in, double cell) {
  Eigen::Vector3d lo = lo_in.array() - 2 * cell;
  lo.z() += 0.5 * cell;
  const Eigen::Vector3d hi = hi_in.array() + 3 * cell;
  const Eigen::Vector3i n = ((hi - lo) / cell).array().ceil().cast<int>() + 1;
  Volume volume;
  // SimpleVolume puts sample i at lo + i * (hi - lo) / n.
  const Eigen::Vector3d top = lo + cell * n.cast<double>();
  volume.Init(vcg::Point3i(n.x(), n.y(), n.z()),
              vcg::Box3f(vcg::Point3f(lo.x(), lo.y(), lo.z()), vcg::Point3f(top.x(), top.y(), top.z())));
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        volume.Val(i, j, k) = static_cast<float>(f(lo + cell * Eigen::Vector3d(i, j, k)));
  McMesh m;
  Walker walker;
  Cubes cubes(m, walker);
  walker.BuildMesh<Cubes>(m, volume, cubes, 0.0f);
  vcg::tri::Clean<McMesh>::RemoveDuplicateVertex(m);
  vcg::tri::Clean<McMesh>::RemoveDegenerateFace(m);
  vcg::tri::Clean<McMesh>::RemoveUnreferencedVertex(m);
  vcg::tri::Allocator<McMesh>::CompactEveryVector(m);

  Surface s;
  s.V.resize(m.vn, 3);
  for (int v = 0; v < m.vn; ++v) s.V.row(v) << m.vert[v].P()[0], m.vert[v].P()[1], m.vert[v].P()[2];
  s.F.resize(m.fn, 3);
  for (int fi = 0; fi < m.fn; ++fi)
    for (int c = 0; c < 3; ++c) s.F(fi, c) = static_cast<int>(vcg::tri::Index(m, m.face[fi].V(c)));
  // Feet cut by the plate: vertices a rounding error off it go onto it.
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    if (std::abs(s.V(v, 2)) < 1e-3 * cell) s.V(v, 2) = 0.0;
  return signed_volume(s) < 0 ? flipped(s) : s;
}

}  // namespace

std::vector<std::string> creature_names() { return {"quadruped", "long_neck", "upright"}; }

Surface creature(const std::string& name, double cell) {
  if (!(cell >= 0.2 && cell <= 5.0)) throw std::invalid_argument("creature: cell must lie in [0.2, 5] mm");
  if (name == "quadruped") return mesh_level_set(quadruped(), {-30, -14, 0}, {38, 14, 48}, cell);
  if (name == "long_neck") return mesh_level_set(long_neck(), {-40, -17, 0}, {40, 17, 52}, cell);
  if (name == "upright") return mesh_level_set(upright(), {-14, -16, 0}, {16, 16, 54}, cell);
  throw std::invalid_argument("creature: unknown name '" + name + "' (quadruped, long_neck, upright)");
}

}  // namespace slim::test

#endif  // SLIM_TESTS_HAVE_VCG
