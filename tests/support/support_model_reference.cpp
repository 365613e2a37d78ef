#include "support/support_model_reference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace slim::test {
namespace {

using Vec2 = Eigen::Vector2d;
constexpr double kStaircase = M_PI / 4.0;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

std::vector<SolidSpan> reference_spans(const Surface& s, const PixelGrid& g, int pixel) {
  const Vec2 c(g.x0 + (pixel % g.nx + 0.5) * g.pixel, g.y0 + (pixel / g.nx + 0.5) * g.pixel);
  std::vector<std::pair<double, int>> hits;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
    const double area = cross2((b - a).head<2>(), (d - a).head<2>());
    if (area == 0) continue;
    const double u = cross2((d - b).head<2>(), c - b.head<2>()) / area;  // weight of a
    const double v = cross2((a - d).head<2>(), c - d.head<2>()) / area;  // weight of b
    const double w = 1.0 - u - v;
    if (u < 0 || v < 0 || w < 0) continue;
    hits.push_back({u * a.z() + v * b.z() + w * d.z(), area > 0 ? -1 : 1});
  }
  std::sort(hits.begin(), hits.end());
  std::vector<SolidSpan> out;
  int winding = 0;
  double start = 0.0;
  for (const auto& [z, turn] : hits) {
    const int before = winding;
    winding += turn;
    if (before == 0 && winding != 0) start = z;
    if (before != 0 && winding == 0) out.push_back({start, z});
  }
  return out;
}

bool reference_overlaps(const PixelGrid& g, int pixel, const Vec2& a, const Vec2& b, const Vec2& c) {
  std::vector<Vec2> poly = {a, b, c};
  const double lo[2] = {g.x0 + (pixel % g.nx) * g.pixel, g.y0 + (pixel / g.nx) * g.pixel};
  for (int axis = 0; axis < 2; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double bound = lo[axis] + side * g.pixel;
      auto inside = [&](const Vec2& p) { return side == 0 ? p[axis] >= bound : p[axis] <= bound; };
      std::vector<Vec2> next;
      for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2& p = poly[i];
        const Vec2& q = poly[(i + 1) % poly.size()];
        if (inside(p)) next.push_back(p);
        if (inside(p) != inside(q)) next.push_back(p + (q - p) * ((bound - p[axis]) / (q[axis] - p[axis])));
      }
      poly.swap(next);
      if (poly.empty()) return false;
    }
  }
  return true;
}

namespace {

// Per pixel and layer: filled by the part at the layer's slice, trimmed, blocked (filled here or
// just above), stopping a column (blocked, and so are its four neighbours, or the outline between
// them lies in the neighbour's half), a top, a contact.
struct Voxels {
  int n = 0, layers = 0;
  std::vector<char> solid, trim, block, stop, top, contact, dense;
  char& at(std::vector<char>& v, int p, int k) { return v[static_cast<size_t>(p) * layers + k]; }
};

Voxels voxels(const SupportRaster& r, const SlicerLayers& L, const GridSweepSettings& s) {
  Voxels v;
  v.n = r.grid.count();
  v.layers = L.count;
  for (auto* a : {&v.solid, &v.trim, &v.block, &v.stop, &v.top, &v.contact, &v.dense}) a->assign(static_cast<size_t>(v.n) * L.count, 0);
  const int reach = static_cast<int>(std::ceil(s.contact_distance / L.height - 1e-9));
  for (int p = 0; p < v.n; ++p)
    for (int k = 0; k < L.count; ++k)
      for (int i = r.span_begin[p]; i < r.span_begin[p + 1]; ++i)
        if (r.spans[i].bottom <= L.slice_z(k) && L.slice_z(k) <= r.spans[i].top) v.at(v.solid, p, k) = 1;
  for (int p = 0; p < v.n; ++p) {
    for (int j = 0; j < L.count; ++j) {
      for (int k = std::max(0, j - reach); k <= std::min(L.count - 1, j + reach); ++k) v.at(v.trim, p, j) |= v.at(v.solid, p, k);
      v.at(v.block, p, j) = v.at(v.solid, p, j) || (j + 1 < L.count && v.at(v.solid, p, j + 1));
      v.at(v.top, p, j) = v.at(v.solid, p, j) && !(j + 1 < L.count && v.at(v.solid, p, j + 1));
    }
  }
  // Whether, at layer k, the part's outline between p (solid, in its run a0..a1) and its free
  // neighbour q lies in q's half: it runs from q's centre at q's next solid layer above (below)
  // to p's centre at a0 (a1), and is past the midpoint from halfway between them on.
  auto outline_in = [&](int p, int q, int k) {
    if (!v.at(v.solid, p, k) || v.at(v.solid, q, k)) return false;
    int a0 = k, a1 = k;
    while (a0 > 0 && v.at(v.solid, p, a0 - 1)) --a0;
    while (a1 + 1 < L.count && v.at(v.solid, p, a1 + 1)) ++a1;
    int up = k + 1, down = k - 1;
    while (up <= a1 && !v.at(v.solid, q, up)) ++up;
    while (down >= a0 && !v.at(v.solid, q, down)) --down;
    return (up <= a1 && 2 * k >= a0 + up) || (down >= a0 && 2 * k <= a1 + down);
  };
  const int nx = r.grid.nx, ny = r.grid.ny;
  for (int p = 0; p < v.n; ++p) {
    const int i = p % nx, row = p / nx;
    if (i == 0 || row == 0 || i + 1 == nx || row + 1 == ny) continue;  // beyond the raster is free
    for (int j = 0; j < L.count; ++j) {
      bool stop = v.at(v.block, p, j);
      for (int q : {p - 1, p + 1, p - nx, p + nx})
        stop = stop && (v.at(v.block, q, j) || outline_in(p, q, j) || (j + 1 < L.count && outline_in(p, q, j + 1)));
      v.at(v.stop, p, j) = stop;
    }
  }
  auto contact_layer = [&](int k) {
    int j = -1;
    for (int i = 0; i < L.count; ++i)
      if (L.print_z(i) <= L.bottom_z(k) - s.contact_distance + 1e-9) j = i;
    return j;
  };
  for (const PixelOverhang& o : r.overhangs) {
    const int lo = o.layer_low, hi = std::min(L.count - 1, o.layer_high);
    if (lo >= L.count) continue;
    const int i = o.pixel % nx, row = o.pixel / nx;
    const bool edge = i == 0 || row == 0 || i + 1 == nx || row + 1 == ny;  // beyond the raster is free
    if (lo > 0 && !edge && v.at(v.solid, o.pixel, lo - 1) && v.at(v.solid, o.pixel - 1, lo - 1) &&
        v.at(v.solid, o.pixel + 1, lo - 1) && v.at(v.solid, o.pixel - nx, lo - 1) && v.at(v.solid, o.pixel + nx, lo - 1))
      continue;  // inside the part: hidden

    for (int j = std::max(0, contact_layer(lo)); j <= contact_layer(hi); ++j) {
      v.at(v.contact, o.pixel, j) = 1;
      if (o.dense) v.at(v.dense, o.pixel, j) = 1;
    }
  }
  return v;
}

// The first layer by its definition: the base columns' free pixels, grown in alternating 4- and
// 8-neighbour steps around the part's first slice, less the interface columns' pixels.
double first_layer(Voxels& v, const PixelGrid& g, const GridSweepSettings& s, const SweepRates& rate,
                   const std::vector<int>& cell, const std::vector<char>& column, const std::vector<char>& interface) {
  std::vector<char> region(static_cast<size_t>(v.n), 0);
  for (int p = 0; p < v.n; ++p) region[p] = column[cell[p]] && !v.at(v.trim, p, 0);
  const int steps = static_cast<int>(std::lround(s.first_layer_expansion / g.pixel));
  for (int step = 0; step < steps; ++step) {
    std::vector<char> next = region;
    for (int p = 0; p < v.n; ++p) {
      if (region[p] || v.at(v.solid, p, 0)) continue;
      const int i = p % g.nx, j = p / g.nx;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const bool diagonal = di != 0 && dj != 0;
          if ((di == 0 && dj == 0) || (diagonal && step % 2 == 0)) continue;
          const int a = i + di, b = j + dj;
          if (a >= 0 && b >= 0 && a < g.nx && b < g.ny && region[a + g.nx * b]) next[p] = 1;
        }
    }
    region.swap(next);
  }
  for (int p = 0; p < v.n; ++p) region[p] = region[p] && !interface[cell[p]];
  double area = 0, outline = 0, along = 0;
  for (int p = 0; p < v.n; ++p) {
    if (!region[p]) continue;
    area += 1;
    const int i = p % g.nx, j = p / g.nx;
    const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
    for (const auto& ab : nb) {
      const bool in = ab[0] >= 0 && ab[1] >= 0 && ab[0] < g.nx && ab[1] < g.ny;
      if (in && region[ab[0] + g.nx * ab[1]]) continue;
      outline += 1;
      if (in && v.at(v.solid, ab[0] + g.nx * ab[1], 0)) along += 1;
    }
  }
  area = std::max(0.0, area * g.pixel * g.pixel - s.xy_gap * along * g.pixel * kStaircase);
  outline *= g.pixel * kStaircase;
  return rate.first_fill_per_mm2 * std::max(0.0, area - rate.first_inset * outline) + rate.first_sheath_per_mm * outline;
}

}  // namespace

namespace {

// One phase's cells, pixel by pixel.
struct Phase {
  int S, ox, oy, cx, cells;
  std::vector<int> cell;
  std::vector<std::vector<int>> members;
  Phase(const PixelGrid& g, int per_cell, int ox_, int oy_) : S(per_cell), ox(ox_), oy(oy_) {
    cx = (g.nx + S - 1) / S + 1;
    cells = cx * ((g.ny + S - 1) / S + 1);
    cell.resize(static_cast<size_t>(g.count()));
    members.resize(static_cast<size_t>(cells));
    for (int p = 0; p < g.count(); ++p) {
      cell[p] = (p % g.nx + S - ox) / S + cx * ((p / g.nx + S - oy) / S);
      members[cell[p]].push_back(p);
    }
  }
};

struct LayerSums {
  double base = 0, iface = 0, outline = 0, fill = 0, contact = 0;
};

// Half of every zigzag link, row by row: in each run of base cells, the fill lines above the run
// (cells whose row above is base too) and below it, as segments. The outermost segment ends on
// either side link along the outline: out to the run's end, one cell side (less its trimmed
// pixels), and back. An inner end of a line above links (one cell side) only to an inner end of a
// line below in the same cell.
template <class IsBase>
double zigzag_links(const Phase& ph, const IsBase& is_base, const std::vector<std::array<int, 4>>& trims, double px) {
  const int S = ph.S, cx = ph.cx;
  double links = 0.0;
  for (int row = 0; row * cx < ph.cells; ++row) {
    for (int x0 = 0; x0 < cx;) {
      if (!is_base(row * cx + x0)) {
        ++x0;
        continue;
      }
      int x1 = x0;
      while (x1 + 1 < cx && is_base(row * cx + x1 + 1)) ++x1;
      std::vector<int> upper, lower;  // columns of the run with a line above / below
      for (int x = x0; x <= x1; ++x) {
        if (is_base(row * cx + x + cx)) upper.push_back(x);
        if (is_base(row * cx + x - cx)) lower.push_back(x);
      }
      if (!upper.empty() && !lower.empty()) {
        // The outer ends: left (side 0) and right (side 1).
        links += 0.5 * ((S - trims[row * cx + x0][0]) + (upper.front() - x0 + lower.front() - x0) * S) * px;
        links += 0.5 * ((S - trims[row * cx + x1][1]) + (x1 - upper.back() + x1 - lower.back()) * S) * px;
      }
      // Inner ends: a segment of a line that is not the outermost ends where the next cell lacks it.
      auto has = [](const std::vector<int>& xs, int x) { return std::binary_search(xs.begin(), xs.end(), x); };
      for (int x : upper) {
        if (x != upper.back() && !has(upper, x + 1) && has(lower, x) && !has(lower, x + 1) && x < lower.back())
          links += 0.5 * (S - trims[row * cx + x][1]) * px;
        if (x != upper.front() && !has(upper, x - 1) && has(lower, x) && !has(lower, x - 1) && x > lower.front())
          links += 0.5 * (S - trims[row * cx + x][0]) * px;
      }
      x0 = x1 + 1;
    }
  }
  return links;
}

// Layer j's columns by their definition: areas, the base islands' sheath and fill lines.
LayerSums layer_sums(Voxels& v, const PixelGrid& g, const GridSweepSettings& s, const SweepRates& rate, const Phase& ph,
                     const std::vector<char>& now, const std::vector<double>& weight, int j) {
  const int S = ph.S, cx = ph.cx;
  const double px = g.pixel, p2 = px * px;
  auto is_base = [&](int c) { return c >= 0 && c < ph.cells && now[c] && weight[c] < 0.5; };
  LayerSums sum;
  std::vector<std::array<int, 4>> trims(static_cast<size_t>(ph.cells), {0, 0, 0, 0});
  for (int c = 0; c < ph.cells; ++c) {
    if (!now[c]) continue;
    int trimmed = 0, edges = 0, side_trimmed[4] = {0, 0, 0, 0};
    bool contact = false;
    for (int p : ph.members[c]) {
      const int i = p % g.nx, jj = p / g.nx, li = (i + S - ph.ox) % S, lj = (jj + S - ph.oy) % S;
      contact |= v.at(v.contact, p, j) != 0;
      if (v.at(v.trim, p, j)) {
        ++trimmed;
        const bool on[4] = {li == 0, li == S - 1, lj == 0, lj == S - 1};
        for (int k = 0; k < 4; ++k) side_trimmed[k] += on[k];
        continue;
      }
      const int nb[4][2] = {{i - 1, jj}, {i + 1, jj}, {i, jj - 1}, {i, jj + 1}};
      for (const auto& ab : nb)
        if (ab[0] >= 0 && ab[1] >= 0 && ab[0] < g.nx && ab[1] < g.ny && v.at(v.trim, ab[0] + g.nx * ab[1], j)) ++edges;
    }
    const double area = std::max(0.0, (S * S - trimmed) * p2 - s.xy_gap * edges * px * kStaircase);
    sum.base += (1 - weight[c]) * area;
    sum.iface += weight[c] * area;
    if (contact) sum.contact += area;
    if (weight[c] >= 0.5) continue;
    const int nbc[4] = {c - 1, c + 1, c - cx, c + cx};
    if (s.sheath) {
      sum.outline += edges * px * kStaircase;
      for (int k = 0; k < 4; ++k)
        if (!is_base(nbc[k])) sum.outline += (S - side_trimmed[k]) * px;
    }
    // A fill line on the boundary with the base cell above (its free pixels on both sides), short
    // of fill_end at each end; its links are counted row by row (zigzag_links).
    const bool up = is_base(c + cx);
    if (up) {
      int up_trimmed = 0;
      for (int p : ph.members[c + cx]) up_trimmed += (p / g.nx + S - ph.oy) % S == 0 && v.at(v.trim, p, j);
      sum.fill += std::min(S - side_trimmed[3], S - up_trimmed) * px;
    }
    for (int side : {-1, 1})
      if (up && !(is_base(c + side) && is_base(c + cx + side))) sum.fill -= rate.fill_end;
    trims[c] = {side_trimmed[0], side_trimmed[1], side_trimmed[2], side_trimmed[3]};
  }
  sum.fill += zigzag_links(ph, is_base, trims, px);
  return sum;
}

}  // namespace

GridSweepResult reference_sweep(const SupportRaster& r, const SlicerLayers& L, const GridSweepSettings& s, int ox, int oy) {
  Voxels v = voxels(r, L, s);
  const PixelGrid& g = r.grid;
  const Phase ph(g, s.pixels_per_cell, ox, oy);
  const double p2 = g.pixel * g.pixel;
  std::vector<char> has_contact(static_cast<size_t>(L.count), 0);
  for (int p = 0; p < v.n; ++p)
    for (int j = 0; j < L.count; ++j) has_contact[j] |= v.at(v.contact, p, j);
  std::vector<SweepRates> rates;
  for (double t : support_layer_thickness(has_contact, L, s.max_support_layer_height)) rates.push_back(sweep_rates(s, L, t));
  const size_t cells = static_cast<size_t>(ph.cells);
  std::vector<char> above(cells, 0), now(cells, 0);
  std::vector<double> dense(cells, 1e9), depth(cells, 0), weight(cells, 0);
  GridSweepResult out;
  for (int j = L.count - 1; j >= 0; --j) {
    for (int c = 0; c < ph.cells; ++c) {
      bool contact = false, has_dense = false, pass = false;
      int tops = 0;
      for (int p : ph.members[c]) {
        contact |= v.at(v.contact, p, j) != 0;
        has_dense |= v.at(v.dense, p, j) != 0;
        pass |= !v.at(v.stop, p, j);
        tops += v.at(v.top, p, j);
      }
      if (above[c]) {
        out.landing_area += tops * p2;
        out.bottom_interface += tops * p2 * rates[j].bottom_interface_per_mm2;
      }
      now[c] = (contact && j > 0) || (above[c] && pass);  // a contact in the first layer alone builds nothing
      dense[c] = !now[c] ? 1e9 : has_dense ? 0 : above[c] ? dense[c] + 1 : 1e9;
      if (now[c] && has_dense) depth[c] = rates[j].interface_depth;
      weight[c] = std::clamp(depth[c] - dense[c], 0.0, 1.0);
    }
    const LayerSums sum = layer_sums(v, g, s, rates[j], ph, now, weight, j);
    const double t = L.thickness(j);
    out.contact_area += sum.contact;
    out.column_volume += t * (sum.base + sum.iface);
    if (j > 0) {
      out.base_fill += t * std::max(0.0, sum.fill) * rates[j].line_per_mm2;
      out.sheath += t * sum.outline * rates[j].line_per_mm2;
      out.top_interface += t * sum.iface * rates[j].interface_per_mm3;
    } else {  // the base grown, the interface as it is
      std::vector<char> base(cells, 0), interface(cells, 0);
      for (size_t c = 0; c < cells; ++c) (weight[c] < 0.5 ? base : interface)[c] = now[c];
      out.top_interface += t * sum.iface * rates[0].interface_per_mm3;
      out.first_layer = first_layer(v, g, s, rates[0], ph.cell, base, interface);
    }
    above = now;
  }
  return out;
}

}  // namespace slim::test
