#include "core/region_extent.h"

#include <algorithm>

#include "core/face_adjacency.h"

namespace slim {
namespace {

// The steepest wall outside the regions at vertex v: the largest horizontal run per height of the
// faces around it that look down and rise from it (side = +1) or fall from it (side = -1).
double wall_run(const Surface& s, const FaceAdjacency& adj, const std::vector<char>& in_region, int v, double side) {
  double run = 0.0;
  for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) {
    if (in_region[*f]) continue;
    const Eigen::Vector3d n = face_cross(s.V, s.F, *f);
    double rise = 0.0;
    for (int u : adj.face(*f)) rise += s.V(u, 2) - s.V(v, 2);
    if (n.z() < 0 && n.head<2>().norm() > 0 && side * rise > 0) run = std::max(run, -n.z() / n.head<2>().norm());
  }
  return run;
}

}  // namespace

std::vector<RegionExtent> region_extents(const Surface& s, const FaceAdjacency& adj, const std::vector<char>& in_region) {
  const int nv = static_cast<int>(s.V.rows());
  std::vector<RegionExtent> out(static_cast<size_t>(nv));
  std::vector<int> order;
  for (int v = 0; v < nv; ++v) {
    bool in = false;
    for (const int* f = adj.faces_begin(v); f != adj.faces_end(v) && !in; ++f) in = in_region[*f] != 0;
    if (!in) continue;
    const double z = s.V(v, 2);
    out[v] = {z, wall_run(s, adj, in_region, v, 1.0), z, wall_run(s, adj, in_region, v, -1.0)};
    order.push_back(v);
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return s.V(a, 2) > s.V(b, 2); });
  // Downwards, every higher neighbour along a region face is final when v is reached; upwards, the
  // same for every lower one.
  auto spread = [&](int v, bool up) {
    for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) {
      if (!in_region[*f]) continue;
      for (int u : adj.face(*f)) {
        RegionExtent &to = out[v], &from = out[u];
        if (up && s.V(u, 2) > s.V(v, 2) && from.top > to.top) to.top = from.top, to.run_above = from.run_above;
        if (!up && s.V(u, 2) < s.V(v, 2) && from.bottom < to.bottom) to.bottom = from.bottom, to.run_below = from.run_below;
      }
    }
  };
  for (int v : order) spread(v, true);
  for (auto v = order.rbegin(); v != order.rend(); ++v) spread(*v, false);
  return out;
}

ShownHeights shown_heights(double z_low, double z_high, double run, const RegionExtent& e, const SlicePlanes& planes,
                           double margin) {
  // How far the surface reaches from the slice below layer k to layer k's own: the wall below up
  // to the region's bottom, the region up to its top, the wall above.
  auto reach_in = [&](double k) {
    const double below = planes.slice_z(k - 1), above = planes.slice_z(k);
    const double from = std::clamp(e.bottom, below, above), to = std::clamp(e.top, from, above);
    return (from - below) * e.run_below + (to > from ? (to - from) * run : 0.0) + (above - to) * e.run_above;
  };
  ShownHeights out;
  if (!std::isfinite(run)) return out;  // a level feature appears all at once
  const double k_high = planes.layer_of(z_high), k_low = planes.layer_of(z_low);
  if (k_high >= 2 && planes.layer_of(e.top) == k_high && reach_in(k_high) < margin) out.high = planes.slice_z(k_high - 1) - 1e-6;
  if (k_low >= 2 && planes.layer_of(e.bottom) == k_low && reach_in(k_low) < margin) out.low = planes.slice_z(k_low) + 1e-6;
  return out;
}

}  // namespace slim
