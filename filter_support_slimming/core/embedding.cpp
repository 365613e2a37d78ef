#include "core/embedding.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace slim {

namespace {

// Loops shorter than this run on one thread: on a busy machine a parallel region can cost
// milliseconds, more than the work.
constexpr Eigen::Index kParallelItems = 8192;

// How a domain finds the tets near a point or a triangle. Everything is computed in the
// locator's working coordinates W (grid cell units for the voxel domain, world units about the
// domain's centre otherwise); area_scale turns working areas into mm².
class Locator {
 public:
  virtual ~Locator() = default;
  // Tets that may contain w (a superset; in a deterministic order).
  virtual void point_candidates(const Eigen::Vector3d& w, std::vector<int>& out) const = 0;
  // Tets that may meet the triangle (a superset, each once, in a deterministic order).
  virtual void triangle_candidates(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                   std::vector<int>& out) const = 0;
  virtual Eigen::Vector4d barycentric(int t, const Eigen::Vector3d& w) const = 0;
  // The four planes of tet t, inward; a face shared by two tets yields exactly negated values.
  virtual TetPlanes planes(int t) const = 0;

  Points W;                 // #V by 3 surface vertices in working coordinates
  double area_scale = 1.0;  // mm² per working area unit
  double plane_eps = 0.0;   // points this close to a tet plane are "on" it (working units)
};

// Voxel domain: the grid cell of a point is its floor; a tet's cell and Kuhn index follow from
// its number (6 per kept cell).
class VoxelLocator : public Locator {
 public:
  VoxelLocator(const Surface& s, const VoxelDomain& d) : dom_(d) {
    const VoxelGrid& g = d.grid;
    W = ((s.V * g.axes.transpose()).rowwise() - g.low.transpose()) / g.cell_size;
    area_scale = g.cell_size * g.cell_size;
    plane_eps = 1e-9;
  }

  void point_candidates(const Eigen::Vector3d& w, std::vector<int>& out) const override {
    constexpr double tol = 1e-9;  // cells this close also hold the point
    Eigen::Vector3i lo, hi;
    for (int a = 0; a < 3; ++a) {
      const int n = dom_.grid.cells(a);
      lo(a) = std::clamp(static_cast<int>(std::floor(w(a) - tol)), 0, n - 1);
      hi(a) = std::clamp(static_cast<int>(std::floor(w(a) + tol)), 0, n - 1);
    }
    for (int k = lo(2); k <= hi(2); ++k)
      for (int j = lo(1); j <= hi(1); ++j)
        for (int i = lo(0); i <= hi(0); ++i) add_cell(i, j, k, out);
  }

  void triangle_candidates(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           std::vector<int>& out) const override {
    cells_overlapping_triangle(dom_.grid, a, b, c, 1e-9, [&](int i, int j, int k) { add_cell(i, j, k, out); });
  }

  Eigen::Vector4d barycentric(int t, const Eigen::Vector3d& w) const override {
    return kuhn_barycentric(t % 6, w - cell_of(t).cast<double>());
  }

  TetPlanes planes(int t) const override { return kuhn_planes(cell_of(t), t % 6); }

 private:
  void add_cell(int i, int j, int k, std::vector<int>& out) const {
    const int rank = dom_.cell_rank[static_cast<size_t>(dom_.grid.cell_index(i, j, k))];
    if (rank < 0) return;
    for (int p = 0; p < 6; ++p) out.push_back(6 * rank + p);
  }
  Eigen::Vector3i cell_of(int t) const {
    const std::int64_t c = dom_.kept_cells[static_cast<size_t>(t / 6)];
    const std::int64_t nx = dom_.grid.cells(0), ny = dom_.grid.cells(1);
    return Eigen::Vector3i(static_cast<int>(c % nx), static_cast<int>((c / nx) % ny), static_cast<int>(c / (nx * ny)));
  }
  const VoxelDomain& dom_;
};

// Any tet mesh: a uniform grid of buckets, each listing the tets whose bounding box meets it.
class BucketLocator : public Locator {
 public:
  BucketLocator(const Surface& s, const TetMesh& m) : mesh_(m) {
    if (m.V.rows() == 0 || m.T.rows() == 0) throw std::invalid_argument("the tet domain is empty");
    if (!m.V.allFinite()) throw std::invalid_argument("the tet domain has a non-finite vertex");
    if (m.T.minCoeff() < 0 || m.T.maxCoeff() >= m.V.rows())
      throw std::invalid_argument("the tet domain refers to a vertex it does not have");
    const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
    centre_ = 0.5 * (lo + hi);
    Vw_ = m.V.rowwise() - centre_;
    W = s.V.rowwise() - centre_;
    const double diag = (hi - lo).norm();
    plane_eps = 1e-12 * diag;
    // About one bucket per tet, cubic buckets.
    const Eigen::Vector3d extent = (hi - lo).transpose() + Eigen::Vector3d::Constant(1e-9 * diag);
    const double side = std::cbrt(extent.prod() / static_cast<double>(m.T.rows()));
    for (int a = 0; a < 3; ++a) dims_(a) = std::clamp(static_cast<int>(std::ceil(extent(a) / side)), 1, 1024);
    low_ = (lo - centre_).transpose() - Eigen::Vector3d::Constant(0.5e-9 * diag);
    inv_size_ = dims_.cast<double>().cwiseQuotient(extent);

    const size_t nb = static_cast<size_t>(dims_.prod());
    offsets_.assign(nb + 1, 0);
    auto for_tet_buckets = [&](Eigen::Index t, auto&& visit) {
      Eigen::Vector3d tlo = Vw_.row(m.T(t, 0)).transpose(), thi = tlo;
      for (int c = 1; c < 4; ++c) {
        tlo = tlo.cwiseMin(Vw_.row(m.T(t, c)).transpose());
        thi = thi.cwiseMax(Vw_.row(m.T(t, c)).transpose());
      }
      const Eigen::Vector3i b0 = bucket(tlo.array() - plane_eps), b1 = bucket(thi.array() + plane_eps);
      for (int k = b0(2); k <= b1(2); ++k)
        for (int j = b0(1); j <= b1(1); ++j)
          for (int i = b0(0); i <= b1(0); ++i) visit(index(i, j, k));
    };
    for (Eigen::Index t = 0; t < m.T.rows(); ++t) for_tet_buckets(t, [&](size_t b) { ++offsets_[b + 1]; });
    for (size_t b = 0; b < nb; ++b) offsets_[b + 1] += offsets_[b];
    tets_.resize(offsets_[nb]);
    std::vector<size_t> fill(offsets_.begin(), offsets_.end() - 1);
    for (Eigen::Index t = 0; t < m.T.rows(); ++t)
      for_tet_buckets(t, [&](size_t b) { tets_[fill[b]++] = static_cast<int>(t); });
  }

  void point_candidates(const Eigen::Vector3d& w, std::vector<int>& out) const override {
    const Eigen::Vector3i b = bucket(w);
    const size_t i = index(b(0), b(1), b(2));
    out.insert(out.end(), tets_.begin() + static_cast<std::ptrdiff_t>(offsets_[i]),
               tets_.begin() + static_cast<std::ptrdiff_t>(offsets_[i + 1]));
  }

  void triangle_candidates(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           std::vector<int>& out) const override {
    const Eigen::Vector3i b0 = bucket(a.cwiseMin(b).cwiseMin(c)), b1 = bucket(a.cwiseMax(b).cwiseMax(c));
    const size_t first = out.size();
    for (int k = b0(2); k <= b1(2); ++k)
      for (int j = b0(1); j <= b1(1); ++j)
        for (int i = b0(0); i <= b1(0); ++i) {
          const size_t n = index(i, j, k);
          out.insert(out.end(), tets_.begin() + static_cast<std::ptrdiff_t>(offsets_[n]),
                     tets_.begin() + static_cast<std::ptrdiff_t>(offsets_[n + 1]));
        }
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end()), out.end());
  }

  Eigen::Vector4d barycentric(int t, const Eigen::Vector3d& w) const override {
    const Eigen::Vector3d a = corner(t, 0);
    const Eigen::Vector3d m1 = corner(t, 1) - a, m2 = corner(t, 2) - a, m3 = corner(t, 3) - a, r = w - a;
    const double det = m1.dot(m2.cross(m3));
    if (det == 0.0) return Eigen::Vector4d::Constant(-std::numeric_limits<double>::infinity());
    Eigen::Vector4d bary;
    bary(1) = r.dot(m2.cross(m3)) / det;
    bary(2) = m1.dot(r.cross(m3)) / det;
    bary(3) = m1.dot(m2.cross(r)) / det;
    bary(0) = 1.0 - bary(1) - bary(2) - bary(3);
    return bary;
  }

  TetPlanes planes(int t) const override {
    TetPlanes P;
    for (int m = 0; m < 4; ++m) {
      // The face opposite corner m, from its vertices in index order: both tets on the face
      // compute the same plane, and flipping it to point inwards negates it exactly.
      std::array<int, 3> f{};
      for (int c = 0, n = 0; c < 4; ++c)
        if (c != m) f[static_cast<size_t>(n++)] = mesh_.T(t, c);
      std::sort(f.begin(), f.end());
      const Eigen::Vector3d a = Vw_.row(f[0]).transpose();
      Eigen::Vector3d n = (Vw_.row(f[1]).transpose() - a).cross(Vw_.row(f[2]).transpose() - a);
      const double len = n.norm();
      if (len > 0.0) n /= len;
      double o = -n.dot(a);
      if (n.dot(corner(t, m)) + o < 0.0) {
        n = -n;
        o = -o;
      }
      P.w[static_cast<size_t>(m)] = n;
      P.o[static_cast<size_t>(m)] = o;
    }
    return P;
  }

 private:
  Eigen::Vector3d corner(int t, int c) const { return Vw_.row(mesh_.T(t, c)).transpose(); }
  Eigen::Vector3i bucket(const Eigen::Vector3d& w) const {
    Eigen::Vector3i b;
    for (int a = 0; a < 3; ++a) {
      const double x = std::floor((w(a) - low_(a)) * inv_size_(a));
      b(a) = static_cast<int>(std::clamp(x, 0.0, static_cast<double>(dims_(a) - 1)));
    }
    return b;
  }
  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) + static_cast<size_t>(dims_(0)) * (static_cast<size_t>(j) + static_cast<size_t>(dims_(1)) * static_cast<size_t>(k));
  }

  const TetMesh& mesh_;
  Eigen::RowVector3d centre_;
  Points Vw_;
  Eigen::Vector3i dims_;
  Eigen::Vector3d low_, inv_size_;
  std::vector<size_t> offsets_;
  std::vector<int> tets_;
};

// A convex polygon being clipped (a triangle cut by 4 planes has at most 7 corners; ties on
// nearly degenerate pieces may add a few).
struct Polygon {
  std::array<Eigen::Vector3d, 32> p;
  int n = 0;
};

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

  Polygon buffers[2];
  Polygon* cur = &buffers[0];
  Polygon* next = &buffers[1];
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
    next->n = 0;
    for (int i = 0; i < cur->n; ++i) {
      const size_t si = static_cast<size_t>(i), sj = static_cast<size_t>((i + 1) % cur->n);
      if (in[si] && next->n < 32) next->p[static_cast<size_t>(next->n++)] = cur->p[si];
      if (in[si] != in[sj] && next->n < 32) {
        const double denom = dist[si] - dist[sj];
        const double t = denom != 0.0 ? std::clamp(dist[si] / denom, 0.0, 1.0) : 0.5;
        next->p[static_cast<size_t>(next->n++)] = cur->p[si] + t * (cur->p[sj] - cur->p[si]);
      }
    }
    std::swap(cur, next);
  }
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  for (int i = 1; i + 1 < cur->n; ++i)
    twice_area += (cur->p[static_cast<size_t>(i)] - cur->p[0]).cross(cur->p[static_cast<size_t>(i + 1)] - cur->p[0]);
  return 0.5 * twice_area.norm();
}

// Pieces below this share of their face's area are rounding noise.
constexpr double kNoisePiece = 1e-12;

struct Piece {
  int face, tet;
  double area;
};

// The lowest index at which a parallel loop failed, and why (so the message does not depend on
// the thread count).
struct FirstError {
  std::atomic<Eigen::Index> index{std::numeric_limits<Eigen::Index>::max()};
  std::string message;
  // Never throws: it runs inside OpenMP regions, which an exception must not leave.
  void report(Eigen::Index i, const char* what) noexcept {
#pragma omp critical(slim_embedding_error)
    if (i < index.load()) {
      index = i;
      try {
        message = what;
      } catch (...) {
        message.clear();
      }
    }
  }
  void rethrow() const {
    if (index.load() != std::numeric_limits<Eigen::Index>::max()) throw std::invalid_argument(message);
  }
};

// The tet holding w with the largest smallest barycentric coordinate; -1 if none holds it.
int locate(const Locator& loc, const Eigen::Vector3d& w, double tol, std::vector<int>& scratch, Eigen::Vector4d& bary) {
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
void face_pieces(const Surface& s, const Locator& loc, const Embedding& e, Eigen::Index f, const EmbeddingOptions& o,
                 std::vector<int>& scratch, std::vector<Piece>& out, FirstError& error) {
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
    if (t < 0) error.report(f, ("the centroid of face " + std::to_string(f) + " lies outside the tet domain").c_str());
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
    error.report(f, ("face " + std::to_string(f) + " lies partly outside the tet domain (" +
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

Embedding embed(const Surface& s, const Tets& T, const Locator& loc, const EmbeddingOptions& o) {
  if (!(o.outside_tolerance >= 0.0)) throw std::invalid_argument("the embedding's outside tolerance must be >= 0");
  const Eigen::Index nv = s.V.rows(), nf = s.F.rows();
  Embedding e;
  e.vertex_tet.resize(nv);
  e.vertex_nodes.resize(nv, 4);
  e.vertex_bary.resize(nv, 4);

  FirstError error;
#pragma omp parallel if (nv > kParallelItems)
  {
    std::vector<int> scratch;
#pragma omp for schedule(dynamic, 1024)
    for (Eigen::Index i = 0; i < nv; ++i) {
      try {
        Eigen::Vector4d bary;
        const int t = locate(loc, loc.W.row(i).transpose(), o.outside_tolerance, scratch, bary);
        if (t < 0) {
          error.report(i, ("surface vertex " + std::to_string(i) + " lies outside the tet domain").c_str());
          continue;
        }
        e.vertex_tet(i) = t;
        e.vertex_nodes.row(i) = T.row(t);
        e.vertex_bary.row(i) = bary.transpose();
      } catch (const std::exception& ex) {
        error.report(i, ex.what());
      } catch (...) {
        error.report(i, "unexpected error while embedding a vertex");
      }
    }
  }
  error.rethrow();

  // Pieces in fixed chunks of faces, concatenated in face order whatever the thread count.
  constexpr Eigen::Index kChunk = 4096;
  const Eigen::Index chunks = (nf + kChunk - 1) / kChunk;
  std::vector<std::vector<Piece>> chunk_pieces(static_cast<size_t>(chunks));
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
          error.report(f, ex.what());
        } catch (...) {
          error.report(f, "unexpected error while splitting a face over the tets");
        }
      }
    }
  }
  error.rethrow();

  // CSR by tet (a stable counting sort, so faces stay ascending within a tet).
  const Eigen::Index nt = T.rows();
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
  return e;
}

}  // namespace

Embedding embed_surface(const Surface& surface, const VoxelDomain& domain, const EmbeddingOptions& options) {
  check_surface(surface);
  if (domain.kept_cells.empty() || domain.cell_rank.size() != static_cast<size_t>(domain.grid.cell_count()))
    throw std::invalid_argument("the voxel domain is empty or incomplete");
  const VoxelLocator loc(surface, domain);
  return embed(surface, domain.mesh.T, loc, options);
}

Embedding embed_surface(const Surface& surface, const TetMesh& domain, const EmbeddingOptions& options) {
  check_surface(surface);
  const BucketLocator loc(surface, domain);
  return embed(surface, domain.T, loc, options);
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
