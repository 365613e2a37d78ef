#include "core/domain/tet_locator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/domain/triangle_cells.h"
#include "core/geometry/uniform_grid.h"

namespace slim {

namespace {

class VoxelLocator : public TetLocator {
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

class MeshLocator : public TetLocator {
 public:
  MeshLocator(const Surface& s, const TetMesh& m) : mesh_(m) {
    if (m.V.rows() == 0 || m.T.rows() == 0) throw std::invalid_argument("the tet domain is empty");
    if (!m.V.allFinite()) throw std::invalid_argument("the tet domain has a non-finite vertex");
    if (m.T.minCoeff() < 0 || m.T.maxCoeff() >= m.V.rows())
      throw std::invalid_argument("the tet domain refers to a vertex it does not have");
    const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
    const Eigen::RowVector3d centre = 0.5 * (lo + hi);
    Vw_ = m.V.rowwise() - centre;
    W = s.V.rowwise() - centre;
    const double diag = (hi - lo).norm();
    plane_eps = 1e-12 * diag;
    // About one cell per tet, cubic cells.
    const Eigen::Vector3d extent = (hi - lo).transpose() + Eigen::Vector3d::Constant(1e-9 * diag);
    const double side = std::cbrt(extent.prod() / static_cast<double>(m.T.rows()));
    Eigen::Vector3i dims;
    for (int a = 0; a < 3; ++a) dims(a) = std::clamp(static_cast<int>(std::ceil(extent(a) / side)), 1, 1024);
    const Eigen::Vector3d low = (lo - centre).transpose() - Eigen::Vector3d::Constant(0.5e-9 * diag);
    grid_ = UniformGrid(low, extent.cwiseQuotient(dims.cast<double>()), dims);
    grid_.fill(static_cast<int>(m.T.rows()), [&](int t, Eigen::Vector3d& tlo, Eigen::Vector3d& thi) {
      tlo = thi = corner(t, 0);
      for (int c = 1; c < 4; ++c) {
        tlo = tlo.cwiseMin(corner(t, c));
        thi = thi.cwiseMax(corner(t, c));
      }
      tlo.array() -= plane_eps;
      thi.array() += plane_eps;
    });
  }

  void point_candidates(const Eigen::Vector3d& w, std::vector<int>& out) const override {
    const UniformGrid::Items items = grid_.items(grid_.index(grid_.cell_of(w)));
    out.insert(out.end(), items.begin(), items.end());
  }

  void triangle_candidates(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           std::vector<int>& out) const override {
    const size_t first = out.size();
    grid_.for_cells(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), [&](size_t cell) {
      const UniformGrid::Items items = grid_.items(cell);
      out.insert(out.end(), items.begin(), items.end());
    });
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

  const TetMesh& mesh_;
  Points Vw_;
  UniformGrid grid_;
};

}  // namespace

std::unique_ptr<TetLocator> voxel_locator(const Surface& surface, const VoxelDomain& domain) {
  return std::make_unique<VoxelLocator>(surface, domain);
}

std::unique_ptr<TetLocator> mesh_locator(const Surface& surface, const TetMesh& domain) {
  return std::make_unique<MeshLocator>(surface, domain);
}

}  // namespace slim
