#include "core/volume_keeping.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slim {
namespace {

// Owner of each item (items 0..n-1 in order) listed per owner, items in increasing order: a
// counting sort, so a gather over an owner's items adds them in the order a single pass would.
template <class OwnerOf>
void list_by_owner(int owners, int items, OwnerOf owner_of, std::vector<int>& begin, std::vector<int>& item) {
  begin.assign(static_cast<size_t>(owners) + 1, 0);
  for (int i = 0; i < items; ++i) ++begin[static_cast<size_t>(owner_of(i)) + 1];
  for (int o = 0; o < owners; ++o) begin[static_cast<size_t>(o) + 1] += begin[static_cast<size_t>(o)];
  item.resize(static_cast<size_t>(items));
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (int i = 0; i < items; ++i) item[static_cast<size_t>(fill[static_cast<size_t>(owner_of(i))]++)] = i;
}

void require_in_range(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("volume keeping: " + what);
}

}  // namespace

VolumeKeeping::VolumeKeeping(const Embedding& e, const Triangles& F, Eigen::Index domain_vertices)
    : embedding_(e), F_(F), domain_vertices_(domain_vertices) {
  const Eigen::Index surface = e.vertex_nodes.rows();
  require_in_range(e.vertex_bary.rows() == surface, "the embedding's weights and nodes differ in count");
  require_in_range(F.size() == 0 || (F.minCoeff() >= 0 && F.maxCoeff() < surface),
                   "a face names a vertex the embedding does not hold");
  require_in_range(e.vertex_nodes.size() == 0 || (e.vertex_nodes.minCoeff() >= 0 && e.vertex_nodes.maxCoeff() < domain_vertices),
                   "the embedding names a domain vertex out of range");
  std::vector<int> corner;
  list_by_owner(static_cast<int>(surface), static_cast<int>(3 * F.rows()),
                [&](int c) { return F(c / 3, c % 3); }, corner_begin_, corner);
  corner_others_.resize(corner.size());
  for (size_t j = 0; j < corner.size(); ++j) {
    const int f = corner[j] / 3, k = corner[j] % 3;
    corner_others_[j] = {F(f, (k + 1) % 3), F(f, (k + 2) % 3)};
  }
}

void VolumeKeeping::centred_surface(const Points& V, Points& by_columns, RowPoints& out) const {
  embedded_positions(embedding_, V, by_columns);
  const Eigen::RowVector3d centre = by_columns.colwise().mean();
  out.resize(by_columns.rows(), 3);
  const auto n = static_cast<int>(by_columns.rows());
#pragma omp parallel for schedule(static) if (n > 65536)
  for (int i = 0; i < n; ++i) out.row(i) = by_columns.row(i) - centre;
}

Points VolumeKeeping::load(const Points& V_start) {
  // Vol = 1/6 sum over faces of a · (b x c) about the centroid; d/da = (b x c) / 6 summed over a's
  // faces, which for a closed surface is a third of the area-weighted normals around a. Gathered
  // per vertex over its corners in face order (the sums of a pass that scatters face by face);
  // then taken to the domain in one pass (its few vertices stay in cache).
  centred_surface(V_start, S_, P_);
  const auto surface = static_cast<int>(P_.rows());
  RowPoints& gS = Q_;  // keep()'s buffer, free here
  gS.resize(P_.rows(), 3);
#pragma omp parallel for schedule(static) if (surface > 65536)
  for (int v = 0; v < surface; ++v) {
    Eigen::RowVector3d g = Eigen::RowVector3d::Zero();
    for (int j = corner_begin_[static_cast<size_t>(v)]; j < corner_begin_[static_cast<size_t>(v) + 1]; ++j) {
      const std::array<int, 2>& other = corner_others_[static_cast<size_t>(j)];
      g += P_.row(other[0]).cross(P_.row(other[1])) / 6.0;
    }
    gS.row(v) = g;
  }
  Points out = Points::Zero(domain_vertices_, 3);
  for (Eigen::Index i = 0; i < P_.rows(); ++i)
    for (int k = 0; k < 4; ++k) out.row(embedding_.vertex_nodes(i, k)) += embedding_.vertex_bary(i, k) * gS.row(i);
  return out;
}

double VolumeKeeping::keep(double target, const Points& u, Points& proposed) {
  // The surface moves linearly with lambda (the embedding is linear), and so does its centroid,
  // so Vol(lambda) = (d0 + d1 lambda + d2 lambda^2 + d3 lambda^3) / 6 exactly: one pass over the
  // faces for the coefficients, then Newton's method on the cubic alone. The faces' terms come in
  // blocks, each made on the threads and added in face order.
  centred_surface(proposed, S_, P_);
  centred_surface(u, S_, Q_);
  const auto faces = static_cast<int>(F_.rows());
  constexpr int kBlock = 1 << 15;
  terms_.resize(4, std::min(faces, kBlock));
  Eigen::Vector4d d = Eigen::Vector4d::Zero();
  for (int first = 0; first < faces; first += kBlock) {
    const int count = std::min(kBlock, faces - first);
#pragma omp parallel for schedule(static) if (count > 4096)
    for (int j = 0; j < count; ++j) {
      const int f = first + j;
      const Eigen::RowVector3d a = P_.row(F_(f, 0)), b = P_.row(F_(f, 1)), c = P_.row(F_(f, 2));
      const Eigen::RowVector3d p = Q_.row(F_(f, 0)), q = Q_.row(F_(f, 1)), r = Q_.row(F_(f, 2));
      terms_.col(j) << a.dot(b.cross(c)), p.dot(b.cross(c)) + a.dot(q.cross(c)) + a.dot(b.cross(r)),
          a.dot(q.cross(r)) + p.dot(b.cross(r)) + p.dot(q.cross(c)), p.dot(q.cross(r));
    }
    for (int j = 0; j < count; ++j) d += terms_.col(j);
  }
  d /= 6.0;
  auto volume = [&](double l) { return d(0) + l * (d(1) + l * (d(2) + l * d(3))); };
  auto slope = [&](double l) { return d(1) + l * (2.0 * d(2) + l * 3.0 * d(3)); };
  double lambda = 0.0;
  for (int step = 0; step < 20 && std::abs(volume(lambda) - target) > 1e-12 * std::abs(target); ++step) {
    const double s = slope(lambda);
    if (!(std::abs(s) > 0.0) || !std::isfinite(s)) break;
    const double next = lambda + (target - volume(lambda)) / s;
    if (!std::isfinite(next)) break;
    lambda = next;
  }
  if (lambda != 0.0) proposed += lambda * u;
  return lambda;
}

Points volume_load(const Embedding& e, const Triangles& F, const Points& V_start) {
  return VolumeKeeping(e, F, V_start.rows()).load(V_start);
}

double keep_volume(const Embedding& e, const Triangles& F, double target, const Points& u, Points& proposed) {
  return VolumeKeeping(e, F, proposed.rows()).keep(target, u, proposed);
}

}  // namespace slim
