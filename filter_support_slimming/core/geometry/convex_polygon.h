// Sutherland–Hodgman clipping of a convex polygon by one plane, the kernel of the voxel
// rasterizer (triangle_cells.h: axis-aligned slabs) and of the face pieces (embedding.h: a tet's
// four planes).
//
//   ConvexPolygon<N> poly;  clip_convex_polygon(poly, dist, inside, out [, on_cut]);
//
// Inputs
//   in      a convex polygon of in.n <= N corners (3D points, any units), in order.
//   dist    in.n signed distances of the corners to the plane (any scale: only their ratios along
//           an edge matter).
//   inside  in.n flags: which corners are kept. The caller decides ties (a corner on the plane)
//           and the tolerance; dist only places the cuts.
//   on_cut  called on every new corner where an edge crosses the plane (e.g. to put it on an
//           axis-aligned plane exactly, whatever the rounding); optional.
// Output
//   out     the kept corners and the cuts, in order; at most N corners (more are dropped, which
//           only a polygon that is not convex could ask for).
// A cut lies at P + t (Q - P), t = dist_P / (dist_P - dist_Q) clamped to [0, 1] (0.5 when both
// distances are equal: rounding flagged them differently).
#pragma once

#include <algorithm>
#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace slim {

template <int N>
struct ConvexPolygon {
  std::array<Eigen::Vector3d, N> p;
  int n = 0;
};

struct NoCutFix {
  void operator()(Eigen::Vector3d&) const {}
};

template <int N, class OnCut = NoCutFix>
void clip_convex_polygon(const ConvexPolygon<N>& in, const double* dist, const bool* inside, ConvexPolygon<N>& out,
                         OnCut&& on_cut = OnCut{}) {
  out.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const int j = (i + 1) % in.n;
    const Eigen::Vector3d& P = in.p[static_cast<size_t>(i)];
    const Eigen::Vector3d& Q = in.p[static_cast<size_t>(j)];
    if (inside[i] && out.n < N) out.p[static_cast<size_t>(out.n++)] = P;
    if (inside[i] != inside[j] && out.n < N) {
      const double denom = dist[i] - dist[j];
      const double t = denom != 0.0 ? std::clamp(dist[i] / denom, 0.0, 1.0) : 0.5;
      Eigen::Vector3d X = P + t * (Q - P);
      on_cut(X);
      out.p[static_cast<size_t>(out.n++)] = X;
    }
  }
}

// The polygon's area (fan from its first corner), in squared units.
template <int N>
double polygon_area(const ConvexPolygon<N>& poly) {
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  for (int i = 1; i + 1 < poly.n; ++i)
    twice_area += (poly.p[static_cast<size_t>(i)] - poly.p[0]).cross(poly.p[static_cast<size_t>(i + 1)] - poly.p[0]);
  return 0.5 * twice_area.norm();
}

}  // namespace slim
