#include "core/support_model/region_extent.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>

#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"

namespace slim {
namespace {

// The steepest walls outside the regions at vertex v: the largest horizontal run per height of the
// faces around it that look down and rise from it (above) or fall from it (below).
std::pair<double, double> wall_runs(const Surface& s, const FaceAdjacency& adj, const std::vector<char>& in_region, int v) {
  double above = 0.0, below = 0.0;
  for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) {
    if (in_region[*f]) continue;
    const Eigen::Vector3d n = face_cross(s.V, s.F, *f);
    const double level = n.head<2>().norm();
    if (!(n.z() < 0) || !(level > 0)) continue;
    double rise = 0.0;
    for (int u : adj.face(*f)) rise += s.V(u, 2) - s.V(v, 2);
    if (rise > 0) above = std::max(above, -n.z() / level);
    if (rise < 0) below = std::max(below, -n.z() / level);
  }
  return {above, below};
}

// Vertices sorted by height, highest first (ties by index): an LSD radix sort of the heights'
// order-preserving 64-bit keys, 16 bits a pass.
void sort_by_height(const Surface& s, std::vector<int>& order) {
  auto key = [&](int v) {
    std::uint64_t bits;
    const double z = s.V(v, 2) + 0.0;  // -0 and +0 alike
    std::memcpy(&bits, &z, sizeof bits);
    bits = (bits >> 63) ? ~bits : bits | (std::uint64_t{1} << 63);  // ascending as unsigned
    return ~bits;  // highest first
  };
  std::vector<std::uint64_t> keys(order.size()), keys_next(order.size());
  for (size_t i = 0; i < order.size(); ++i) keys[i] = key(order[i]);
  std::vector<int> next(order.size());
  for (int shift = 0; shift < 64; shift += 16) {
    std::vector<size_t> count((1 << 16) + 1, 0);
    for (std::uint64_t k : keys) ++count[((k >> shift) & 0xFFFF) + 1];
    for (size_t d = 1; d < count.size(); ++d) count[d] += count[d - 1];
    for (size_t i = 0; i < order.size(); ++i) {
      const size_t at = count[(keys[i] >> shift) & 0xFFFF]++;
      next[at] = order[i];
      keys_next[at] = keys[i];
    }
    order.swap(next);
    keys.swap(keys_next);
  }
}

}  // namespace

std::vector<RegionExtent> region_extents(const Surface& s, const FaceAdjacency& adj, const std::vector<char>& in_region) {
  const int nv = static_cast<int>(s.V.rows());
  std::vector<RegionExtent> out(static_cast<size_t>(nv));
  std::vector<char> in(static_cast<size_t>(nv), 0);
  for (int f = 0; f < s.F.rows(); ++f)
    if (in_region[f])
      for (int k = 0; k < 3; ++k) in[s.F(f, k)] = 1;
  std::vector<int> order;  // the regions' vertices, highest first
  for (int v = 0; v < nv; ++v)
    if (in[v]) order.push_back(v);
  parallel_for(static_cast<int>(order.size()), [&](int i) {
    const int v = order[i];
    const double z = s.V(v, 2);
    const auto [above, below] = wall_runs(s, adj, in_region, v);
    out[v] = {z, above, z, below};
  });
  sort_by_height(s, order);
  // Downwards, every higher neighbour along a region face is final when v is reached; upwards, the
  // same for every lower one.
  auto spread = [&](int v, bool up) {
    RegionExtent& to = out[v];
    const double z = s.V(v, 2);
    for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f) {
      if (!in_region[*f]) continue;
      for (int u : adj.face(*f)) {
        const RegionExtent& from = out[u];
        if (up && s.V(u, 2) > z && from.top > to.top) to.top = from.top, to.run_above = from.run_above;
        if (!up && s.V(u, 2) < z && from.bottom < to.bottom) to.bottom = from.bottom, to.run_below = from.run_below;
      }
    }
  };
  // The two spreads touch different fields: one thread each.
  parallel_for(2, [&](int down) {
    if (!down)
      for (int v : order) spread(v, true);
    else
      for (auto it = order.rbegin(); it != order.rend(); ++it) spread(*it, false);
  });
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
