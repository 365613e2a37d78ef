#include "core/domain/embedding.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/domain/tet_locator.h"
#include "core/geometry/convex_polygon.h"
#include "core/platform/parallel_for.h"

namespace slim {

namespace {

// Loops shorter than this run on one thread: on a busy machine a parallel region can cost
// milliseconds, more than the work.
constexpr Eigen::Index kParallelItems = 8192;

// Area of the part of triangle (a, b, c) inside the tet with these planes (Sutherland–Hodgman).
// A point within eps of a plane is treated as moved a little along `shift` (the face's back
// side), so a face lying in a plane shared by two tets goes to exactly one of them.
double clipped_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const TetPlanes& planes,
                    const Eigen::Vector3d& shift, double eps) {
  // Quick answers from the corners alone: entirely outside one plane, or inside all four.
  std::array<bool, 4> tie_inside{};
  bool contained = true;
  for (size_t m = 0; m < 4; ++m) {
    tie_inside[m] = planes.w[m].dot(shift) >= 0.0;
    int inside = 0;
    for (const Eigen::Vector3d* p : {&a, &b, &c}) {
      const double d = planes.w[m].dot(*p) + planes.o[m];
      inside += d > eps || (d >= -eps && tie_inside[m]);
    }
    if (inside == 0) return 0.0;
    contained = contained && inside == 3;
  }
  if (contained) return 0.5 * (b - a).cross(c - a).norm();

  // A triangle cut by 4 planes has at most 7 corners; ties on nearly degenerate pieces may add a few.
  using Clipped = ConvexPolygon<32>;
  Clipped buffers[2];
  Clipped* cur = &buffers[0];
  Clipped* next = &buffers[1];
  cur->p[0] = a;
  cur->p[1] = b;
  cur->p[2] = c;
  cur->n = 3;
  std::array<double, 32> dist;
  std::array<bool, 32> in;
  for (size_t m = 0; m < 4; ++m) {
    int inside = 0;
    for (int i = 0; i < cur->n; ++i) {
      const size_t si = static_cast<size_t>(i);
      dist[si] = planes.w[m].dot(cur->p[si]) + planes.o[m];
      in[si] = dist[si] > eps || (dist[si] >= -eps && tie_inside[m]);
      inside += in[si];
    }
    if (inside == 0) return 0.0;
    if (inside == cur->n) continue;
    clip_convex_polygon(*cur, dist.data(), in.data(), *next);
    std::swap(cur, next);
  }
  return polygon_area(*cur);
}

// Pieces below this share of their face's area are rounding noise.
constexpr double kNoisePiece = 1e-12;

struct Piece {
  int face, tet;
  double area;
};

// The tet holding w with the largest smallest barycentric coordinate; -1 if none holds it.
int locate(const TetLocator& loc, const Eigen::Vector3d& w, double tol, std::vector<int>& scratch, Eigen::Vector4d& bary) {
  scratch.clear();
  loc.point_candidates(w, scratch);
  int best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  for (int t : scratch) {
    const Eigen::Vector4d b = loc.barycentric(t, w);
    const double m = b.minCoeff();
    if (m > best_min) {
      best_min = m;
      best = t;
      bary = b;
    }
  }
  return best_min >= -tol ? best : -1;
}

// The pieces of face f, appended to out.
void face_pieces(const Surface& s, const TetLocator& loc, const Embedding& e, Eigen::Index f, const EmbeddingOptions& o,
                 std::vector<int>& scratch, std::vector<Piece>& out, FirstFailure& error) {
  const int face = static_cast<int>(f);
  const std::array<int, 3> v{s.F(f, 0), s.F(f, 1), s.F(f, 2)};
  const Eigen::Vector3d a = loc.W.row(v[0]).transpose(), b = loc.W.row(v[1]).transpose(), c = loc.W.row(v[2]).transpose();
  const Eigen::Vector3d twice_normal = (b - a).cross(c - a);
  const double area = 0.5 * twice_normal.norm() * loc.area_scale;
  if (!(area > 0.0)) {
    out.push_back({face, e.vertex_tet(v[0]), 0.0});
    return;
  }
  if (o.faces == FaceAssignment::centroid) {
    Eigen::Vector4d bary;
    const int t = locate(loc, (a + b + c) / 3.0, o.outside_tolerance, scratch, bary);
    if (t < 0) error.record_invalid_argument(f, ("the centroid of face " + std::to_string(f) + " lies outside the tet domain").c_str());
    out.push_back({face, std::max(t, 0), area});
    return;
  }
  // Most faces of a fine mesh lie inside one tet: the tet of one of their vertices. Vertices
  // strictly inside different tets rule that out (tet interiors are disjoint).
  const std::array<int, 3> vt{e.vertex_tet(v[0]), e.vertex_tet(v[1]), e.vertex_tet(v[2])};
  bool may_fit = vt[0] == vt[1] && vt[1] == vt[2];
  for (int k = 0; k < 3 && !may_fit; ++k) may_fit = e.vertex_bary.row(v[static_cast<size_t>(k)]).minCoeff() <= 1e-9;
  for (size_t k = 0; k < 3 && may_fit; ++k) {
    const int t = vt[k];
    if ((k > 0 && t == vt[0]) || (k > 1 && t == vt[1])) continue;
    if (loc.barycentric(t, a).minCoeff() >= -1e-12 && loc.barycentric(t, b).minCoeff() >= -1e-12 &&
        loc.barycentric(t, c).minCoeff() >= -1e-12) {
      out.push_back({face, t, area});
      return;
    }
  }
  scratch.clear();
  loc.triangle_candidates(a, b, c, scratch);
  const Eigen::Vector3d back = -twice_normal;
  const size_t first = out.size();
  size_t largest = first;
  double covered = 0.0, dropped = 0.0;
  for (int t : scratch) {
    const double piece = clipped_area(a, b, c, loc.planes(t), back, loc.plane_eps) * loc.area_scale;
    covered += piece;
    // A tet that only touches the face along an edge yields rounding noise (~1e-16 of the
    // area); it would still count as a constraint in the local step, so it is dropped.
    if (piece <= kNoisePiece * area) {
      dropped += piece;
      continue;
    }
    if (out.size() > first && piece > out[largest].area) largest = out.size();
    out.push_back({face, t, piece});
  }
  // Clipping is exact only to rounding: a clipped corner can move by about eps times the size of
  // the coordinates, so a needle face (a CAD sliver 1e-12 mm wide, or one vertex 1e30 mm away)
  // loses area that has nothing to do with the domain. Only a shortfall beyond that rounding
  // means "outside"; a smaller one goes to the largest piece, so the pieces sum to the area.
  const double reach = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff()});
  const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
  const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * reach * longest * loc.area_scale;
  if (covered < (1.0 - 1e-6) * area - rounding) {
    error.record_invalid_argument(f, ("face " + std::to_string(f) + " lies partly outside the tet domain (" +
                     std::to_string(100.0 * covered / area) + "% of its area inside)")
                        .c_str());
    return;
  }
  if (out.size() == first) out.push_back({face, e.vertex_tet(v[0]), 0.0});  // all of it lost to rounding
  if (covered > area) {
    // Overlap: tets count what lies within plane_eps of their faces, so a face lying along a
    // tet face (a part flat to 1e-9 of a cell) is counted on both sides. Scale the pieces back.
    const double keep = area / covered;
    for (size_t i = first; i < out.size(); ++i) out[i].area *= keep;
    dropped *= keep;
  }
  out[largest].area += dropped + std::max(0.0, area - covered);  // keeps the sum equal to the area
}

// Every vertex's tet and barycentric coordinates.
void embed_vertices(const Tets& T, const TetLocator& loc, const EmbeddingOptions& o, Embedding& e) {
  const Eigen::Index nv = loc.W.rows();
  e.vertex_tet.resize(nv);
  e.vertex_nodes.resize(nv, 4);
  e.vertex_bary.resize(nv, 4);
  FirstFailure error;
#pragma omp parallel if (nv > kParallelItems)
  {
    std::vector<int> scratch;
#pragma omp for schedule(dynamic, 1024)
    for (Eigen::Index i = 0; i < nv; ++i) {
      try {
        Eigen::Vector4d bary;
        const int t = locate(loc, loc.W.row(i).transpose(), o.outside_tolerance, scratch, bary);
        if (t < 0) {
          error.record_invalid_argument(i, ("surface vertex " + std::to_string(i) + " lies outside the tet domain").c_str());
          continue;
        }
        e.vertex_tet(i) = t;
        e.vertex_nodes.row(i) = T.row(t);
        e.vertex_bary.row(i) = bary.transpose();
      } catch (const std::exception& ex) {
        error.record_invalid_argument(i, ex.what());
      } catch (...) {
        error.record_invalid_argument(i, "unexpected error while embedding a vertex");
      }
    }
  }
  error.rethrow();
}

// Every face's pieces, in fixed chunks of faces, concatenated in face order whatever the thread
// count.
std::vector<std::vector<Piece>> face_pieces_in_chunks(const Surface& s, const TetLocator& loc, const Embedding& e,
                                                      const EmbeddingOptions& o) {
  constexpr Eigen::Index kChunk = 4096;
  const Eigen::Index nf = s.F.rows();
  const Eigen::Index chunks = (nf + kChunk - 1) / kChunk;
  std::vector<std::vector<Piece>> chunk_pieces(static_cast<size_t>(chunks));
  FirstFailure error;
#pragma omp parallel if (nf > kParallelItems)
  {
    std::vector<int> scratch;
#pragma omp for schedule(dynamic, 1)
    for (Eigen::Index ch = 0; ch < chunks; ++ch) {
      auto& out = chunk_pieces[static_cast<size_t>(ch)];
      for (Eigen::Index f = ch * kChunk; f < std::min(nf, (ch + 1) * kChunk); ++f) {
        try {
          face_pieces(s, loc, e, f, o, scratch, out, error);
        } catch (const std::exception& ex) {
          error.record_invalid_argument(f, ex.what());
        } catch (...) {
          error.record_invalid_argument(f, "unexpected error while splitting a face over the tets");
        }
      }
    }
  }
  error.rethrow();
  return chunk_pieces;
}

// The pieces as CSR by tet (a stable counting sort, so faces stay ascending within a tet).
void tet_piece_lists(const std::vector<std::vector<Piece>>& chunk_pieces, Eigen::Index nt, Embedding& e) {
  e.tet_face_offsets = Eigen::VectorXi::Zero(nt + 1);
  size_t total = 0;
  for (const auto& chunk : chunk_pieces) {
    total += chunk.size();
    for (const Piece& p : chunk) ++e.tet_face_offsets(p.tet + 1);
  }
  if (total > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw std::invalid_argument("too many face pieces for 32-bit offsets");
  for (Eigen::Index t = 0; t < nt; ++t) e.tet_face_offsets(t + 1) += e.tet_face_offsets(t);
  e.tet_faces.resize(static_cast<Eigen::Index>(total));
  e.tet_face_areas.resize(static_cast<Eigen::Index>(total));
  Eigen::VectorXi fill = e.tet_face_offsets.head(nt);
  int previous_face = -1;
  bool counted = false;  // previous_face already counted as split
  for (const auto& chunk : chunk_pieces)
    for (const Piece& p : chunk) {
      const int slot = fill(p.tet)++;
      e.tet_faces(slot) = p.face;
      e.tet_face_areas(slot) = p.area;
      if (p.face != previous_face) {
        counted = false;
      } else if (!counted) {
        ++e.split_faces;
        counted = true;
      }
      previous_face = p.face;
    }
}

Embedding embed(const Surface& s, const Tets& T, const TetLocator& loc, const EmbeddingOptions& o) {
  if (!(o.outside_tolerance >= 0.0)) throw std::invalid_argument("the embedding's outside tolerance must be >= 0");
  Embedding e;
  embed_vertices(T, loc, o, e);
  tet_piece_lists(face_pieces_in_chunks(s, loc, e, o), T.rows(), e);
  return e;
}

}  // namespace

Embedding embed_surface(const Surface& surface, const VoxelDomain& domain, const EmbeddingOptions& options) {
  return embed_surface(CheckedSurface(surface), domain, options);
}

Embedding embed_surface(const Surface& surface, const TetMesh& domain, const EmbeddingOptions& options) {
  return embed_surface(CheckedSurface(surface), domain, options);
}

Embedding embed_surface(const CheckedSurface& surface, const VoxelDomain& domain, const EmbeddingOptions& options) {
  if (domain.kept_cells.empty() || domain.cell_rank.size() != static_cast<size_t>(domain.grid.cell_count()))
    throw std::invalid_argument("the voxel domain is empty or incomplete");
  return embed(surface.get(), domain.mesh.T, *voxel_locator(surface.get(), domain), options);
}

Embedding embed_surface(const CheckedSurface& surface, const TetMesh& domain, const EmbeddingOptions& options) {
  return embed(surface.get(), domain.T, *mesh_locator(surface.get(), domain), options);
}

void embedded_positions(const Embedding& e, const Points& domain_V, Points& surface_V) {
  const Eigen::Index n = e.vertex_tet.size();
  surface_V.resize(n, 3);
#pragma omp parallel for schedule(static) if (n > kParallelItems)
  for (Eigen::Index i = 0; i < n; ++i)
    surface_V.row(i) = e.vertex_bary(i, 0) * domain_V.row(e.vertex_nodes(i, 0)) +
                       e.vertex_bary(i, 1) * domain_V.row(e.vertex_nodes(i, 1)) +
                       e.vertex_bary(i, 2) * domain_V.row(e.vertex_nodes(i, 2)) +
                       e.vertex_bary(i, 3) * domain_V.row(e.vertex_nodes(i, 3));
}

}  // namespace slim
