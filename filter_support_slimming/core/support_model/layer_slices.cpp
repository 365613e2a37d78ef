#include "core/support_model/layer_slices.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"

namespace slim {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// What face `face` cuts at one height: from point a on its edge `enter` (vertex enter above the
// height, the next one below) to point b on its edge `leave` (below, then above). Edge k runs from
// F(face, k) to F(face, k + 1 mod 3), so with the faces counter-clockwise seen from outside the
// material lies on the segment's left, seen from above.
struct Segment {
  int face = -1, enter = -1, leave = -1;
  Vec2 a, b;
};

// Where the edge from `below` to `above` meets height z. Both faces of an edge call it with the
// same two vertices in the same roles, so they find the same point, bit for bit.
Vec2 cut(const Vec3& below, const Vec3& above, double z) {
  const double t = (z - below.z()) / (above.z() - below.z());
  return (below + t * (above - below)).head<2>();
}

bool cut_face(const Surface& s, int f, double z, Segment& out) {
  bool up[3];
  for (int k = 0; k < 3; ++k) up[k] = s.V(s.F(f, k), 2) >= z;
  if (up[0] == up[1] && up[1] == up[2]) return false;
  out.face = f;
  for (int k = 0; k < 3; ++k) {
    const int next = (k + 1) % 3;
    if (up[k] == up[next]) continue;
    const Vec3 p = s.V.row(s.F(f, k)), q = s.V.row(s.F(f, next));
    if (up[k]) out.enter = k, out.a = cut(q, p, z);
    else out.leave = k, out.b = cut(p, q, z);
  }
  return true;
}

// Whether segment `next` goes on from `prev`: it enters through the edge `prev` leaves by, run the
// other way (which also rules out the twin of a turned face or a non-manifold guess).
bool continues(const Surface& s, const Segment& prev, const Segment& next) {
  return s.F(prev.face, prev.leave) == s.F(next.face, (next.enter + 1) % 3) &&
         s.F(prev.face, (prev.leave + 1) % 3) == s.F(next.face, next.enter);
}

double length(const Polyline2& p) {
  double l = 0.0;
  for (size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

double signed_area(const Polyline2& p) {
  double a = 0.0;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

struct Chains {
  std::vector<Polyline2> loops, open;
};

// The segments of one height chained through the faces' shared edges. segs: sorted by face.
Chains chain_segments(const Surface& s, const FaceAdjacency& adj, const std::vector<Segment>& segs) {
  auto find = [&](int face) {
    const auto it = std::lower_bound(segs.begin(), segs.end(), face, [](const Segment& x, int f) { return x.face < f; });
    return it != segs.end() && it->face == face ? static_cast<int>(it - segs.begin()) : -1;
  };
  auto after = [&](int i) {
    const int g = adj.across(segs[i].face, segs[i].leave).face, j = g >= 0 ? find(g) : -1;
    return j >= 0 && continues(s, segs[i], segs[j]) ? j : -1;
  };
  auto before = [&](int i) {
    const int g = adj.across(segs[i].face, segs[i].enter).face, j = g >= 0 ? find(g) : -1;
    return j >= 0 && continues(s, segs[j], segs[i]) ? j : -1;
  };
  Chains out;
  std::vector<char> used(segs.size(), 0);
  for (int first = 0; first < static_cast<int>(segs.size()); ++first) {
    if (used[first]) continue;
    used[first] = 1;
    Polyline2 chain = {segs[first].a, segs[first].b};
    bool closed = false;
    for (int i = after(first); i >= 0; i = after(i)) {
      if (i == first) {
        closed = true;
        break;
      }
      if (used[i]) break;
      used[i] = 1;
      chain.push_back(segs[i].b);
    }
    if (closed) {
      chain.pop_back();  // the last point is the first one again
      if (chain.size() >= 3) out.loops.push_back(std::move(chain));
      continue;
    }
    Polyline2 head;  // the chain's start, walked backwards from the first segment
    for (int i = before(first); i >= 0 && !used[i]; i = before(i)) {
      used[i] = 1;
      head.push_back(segs[i].a);
    }
    std::reverse(head.begin(), head.end());
    head.insert(head.end(), chain.begin(), chain.end());
    out.open.push_back(std::move(head));
  }
  return out;
}

struct OpenChain {
  Polyline2 points;
  bool consumed = false;
};

// One round of the slicer's gap closing (see the header), over the chains not consumed yet.
void close_gaps(std::vector<OpenChain>& open, std::vector<Polyline2>& loops, double max_gap, bool reversed) {
  std::vector<int> order;
  std::vector<double> len(open.size(), 0.0);
  for (int i = 0; i < static_cast<int>(open.size()); ++i)
    if (!open[i].consumed) order.push_back(i), len[i] = length(open[i].points);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return len[a] > len[b]; });
  const double gap2 = max_gap * max_gap;
  for (int o : order) {
    OpenChain& c = open[o];
    if (c.consumed) continue;
    c.consumed = true;
    int joined = 1;
    for (;;) {
      const Vec2 end = c.points.back();
      int best = -1;
      bool best_start = true;
      double best_d2 = gap2;
      for (int q : order) {  // the nearest end of another chain within the gap
        if (open[q].consumed) continue;
        for (bool at_start : {true, false}) {
          if (!at_start && !reversed) continue;
          const double d2 = (end - (at_start ? open[q].points.front() : open[q].points.back())).squaredNorm();
          if (d2 < best_d2) best = q, best_start = at_start, best_d2 = d2;
        }
      }
      const double close2 = (end - c.points.front()).squaredNorm();
      bool close = close2 < gap2;
      if (best >= 0 && close && close2 < best_d2) close = std::sqrt(close2) < 0.3 * length(c.points);
      if (close) {
        if (close2 == 0) c.points.pop_back();
        if (c.points.size() >= 3) {
          if (reversed && joined > 1 && signed_area(c.points) < 0) std::reverse(c.points.begin(), c.points.end());
          loops.push_back(std::move(c.points));
        }
        c.points.clear();
        break;
      }
      if (best < 0) {
        c.consumed = false;
        break;
      }
      Polyline2& more = open[best].points;
      if (!best_start) std::reverse(more.begin(), more.end());
      c.points.insert(c.points.end(), more.begin() + (more.front() == end ? 1 : 0), more.end());
      ++joined;
      open[best].consumed = true;
      more.clear();
    }
  }
}

LayerSlice slice_one(const Surface& s, const FaceAdjacency& adj, const int* faces, const int* faces_end, double z,
                     double max_gap) {
  std::vector<Segment> segs;
  segs.reserve(static_cast<size_t>(faces_end - faces));
  for (const int* f = faces; f != faces_end; ++f) {
    Segment seg;
    if (cut_face(s, *f, z, seg)) segs.push_back(seg);
  }
  Chains chains = chain_segments(s, adj, segs);
  LayerSlice out;
  out.loops = std::move(chains.loops);
  std::vector<OpenChain> open;
  for (Polyline2& p : chains.open) open.push_back({std::move(p), false});
  close_gaps(open, out.loops, max_gap, false);
  close_gaps(open, out.loops, max_gap, true);
  for (OpenChain& c : open)
    if (!c.consumed && !c.points.empty()) out.dropped.push_back(std::move(c.points));
  return out;
}

}  // namespace

std::vector<LayerSlice> slice_layers(const Surface& s, const FaceAdjacency& adj, const std::vector<double>& heights,
                                     double max_gap) {
  if (!(max_gap >= 0)) throw std::invalid_argument("slice layers: the gap to close must not be negative");
  for (double h : heights)
    if (!std::isfinite(h)) throw std::invalid_argument("slice layers: a slice height is not finite");
  const int nh = static_cast<int>(heights.size());
  std::vector<int> order(static_cast<size_t>(nh));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return heights[a] < heights[b]; });
  std::vector<double> sorted(static_cast<size_t>(nh));
  for (int i = 0; i < nh; ++i) sorted[i] = heights[order[i]];
  // The heights each face crosses, [lo, hi) in sorted order (below z < h <= top z), then the
  // faces of every height in increasing order (a counting sort).
  const int nf = static_cast<int>(s.F.rows());
  std::vector<int> lo(static_cast<size_t>(nf)), hi(static_cast<size_t>(nf)), begin(static_cast<size_t>(nh) + 1, 0);
  for (int f = 0; f < nf; ++f) {
    const double z0 = s.V(s.F(f, 0), 2), z1 = s.V(s.F(f, 1), 2), z2 = s.V(s.F(f, 2), 2);
    lo[f] = static_cast<int>(std::upper_bound(sorted.begin(), sorted.end(), std::min({z0, z1, z2})) - sorted.begin());
    hi[f] = static_cast<int>(std::upper_bound(sorted.begin(), sorted.end(), std::max({z0, z1, z2})) - sorted.begin());
    for (int h = lo[f]; h < hi[f]; ++h) ++begin[h + 1];
  }
  for (int h = 0; h < nh; ++h) begin[h + 1] += begin[h];
  std::vector<int> faces(static_cast<size_t>(begin[nh])), fill(begin.begin(), begin.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int h = lo[f]; h < hi[f]; ++h) faces[fill[h]++] = f;
  std::vector<LayerSlice> out(static_cast<size_t>(nh));
  parallel_for(nh, [&](int h) {
    out[order[h]] = slice_one(s, adj, faces.data() + begin[h], faces.data() + begin[h + 1], sorted[h], max_gap);
  });
  return out;
}

}  // namespace slim
