// GridSupportSweep::run: one grid phase swept down over the events (support_sweep.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/support_model/support_sweep.h"

namespace slim {
namespace {

constexpr double kStaircase = M_PI / 4.0;  // mean true length of a pixel outline per pixel edge
constexpr int kNoDense = 1 << 29;

}  // namespace

namespace {

// One phase's cells: which cell every pixel lies in, and on which of its sides.
struct CellMap {
  int cx = 0, cy = 0;               // cells along x and y
  std::vector<int> cell;            // per pixel
  std::vector<std::uint8_t> sides;  // per pixel: bit s set when it lies along side s (-x, +x, -y, +y)
  CellMap(const PixelGrid& g, int per_cell, int ox, int oy) {
    cx = (g.nx + per_cell - 1) / per_cell + 1;
    cy = (g.ny + per_cell - 1) / per_cell + 1;
    cell.resize(static_cast<size_t>(g.count()));
    sides.resize(static_cast<size_t>(g.count()));
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const int a = i + per_cell - ox, b = j + per_cell - oy;  // shifted so cells start at the offset
        const int li = a % per_cell, lj = b % per_cell, p = i + g.nx * j;
        cell[p] = a / per_cell + cx * (b / per_cell);
        sides[p] = static_cast<std::uint8_t>((li == 0) | (li == per_cell - 1) << 1 | (lj == 0) << 2 | (lj == per_cell - 1) << 3);
      }
    }
  }
};

// The counters of one phase's cells at the current layer and the columns of the layer above.
struct PhaseState {
  int per_cell;
  struct Counters {
    int kind[GridSupportSweep::kKinds];
    int side_trimmed[4];  // trimmed pixels along each side (-x, +x, -y, +y)
  };
  std::vector<Counters> count;  // per cell
  std::vector<std::uint8_t> column_above, listed_contact;
  std::vector<int> dense_distance, seen, state_layer;
  std::vector<double> interface_weight, dense_depth;
  std::vector<int> above, now, contacts;
  PhaseState(int cells, int per_cell_) : per_cell(per_cell_) {
    count.assign(static_cast<size_t>(cells), Counters{});
    column_above.assign(static_cast<size_t>(cells), 0);
    listed_contact = column_above;
    dense_distance.assign(static_cast<size_t>(cells), kNoDense);
    seen.assign(static_cast<size_t>(cells), -1);
    state_layer = seen;
    interface_weight.assign(static_cast<size_t>(cells), 0.0);
    dense_depth = interface_weight;
  }
  void apply(const GridSupportSweep::Event& e, const CellMap& map) {
    const int c = map.cell[e.pixel];
    Counters& k = count[c];
    k.kind[e.kind] += e.delta;
    if (e.kind == GridSupportSweep::kTrim && map.sides[e.pixel])
      for (int s = 0; s < 4; ++s)
        if (map.sides[e.pixel] >> s & 1) k.side_trimmed[s] += e.delta;
    if (e.kind == GridSupportSweep::kContact && k.kind[e.kind] > 0 && !listed_contact[c]) {
      listed_contact[c] = 1;
      contacts.push_back(c);
    }
  }
};

// The link from the end of the fill line above cell c (on the boundary with the row above) on
// `side` (-1 or +1 along x) to the end of the line below c's row on the same side: the zigzag runs
// along the island's outline, so where the row reaches past either line's end, the link runs out
// along the row to its end, one cell side down, and back in to the other line's end. Where the line
// above goes on further along the row (a notch), its end here links only to a line below that
// ends in this cell and goes on too. In mm; 0 when nothing links.
template <class IsBase>
double zigzag_link(const PhaseState& st, const CellMap& map, const IsBase& base, int c, int side, int S, double p) {
  const int row_begin = c - c % map.cx, row_end = row_begin + map.cx;
  auto in_row = [&](int e) { return e >= row_begin && e < row_end; };
  const int sides = side < 0 ? 0 : 1;
  int out = 0, e = c;
  bool lower_goes_on = false;
  while (in_row(e + side) && base(e + side)) {
    e += side;
    ++out;
    if (base(e + map.cx)) {  // the line above resumes: a notch
      for (int d = c + side; in_row(d) && base(d); d += side) lower_goes_on |= base(d - map.cx);
      const bool lower_ends_here = base(c - map.cx) && !base(c + side - map.cx);
      return lower_ends_here && lower_goes_on ? (S - st.count[c].side_trimmed[sides]) * p : 0.0;
    }
  }
  int back = 0, b = e;  // the outermost cell of the row under which the line below runs
  while (in_row(b) && base(b) && !base(b - map.cx)) {
    b -= side;
    ++back;
  }
  if (!in_row(b) || !base(b)) return 0.0;
  return ((S - st.count[e].side_trimmed[sides]) + static_cast<double>(out + back) * S) * p;
}

// One layer's columns in figures: the base and interface areas, the base islands' outline (cell
// sides facing no base cell, and the part's outline inside base cells) where the sheath runs, and
// the base fill. PrusaSlicer's support lines run along x one grid cell apart, on the cell
// boundaries (its fill pattern is anchored where the grid is), so inside an island they lie on the
// boundaries between base cells, each ending fill_end short of the island's outline, and joined
// into a zigzag by links along the outline.
struct LayerFigures {
  double base_area = 0.0, interface_area = 0.0, outline = 0.0, fill_length = 0.0, contact_area = 0.0;
};

LayerFigures layer_figures(const PhaseState& st, const CellMap& map, const PixelGrid& grid, const GridSweepSettings& settings,
                           double fill_end, int j) {
  const int S = settings.pixels_per_cell, cells = map.cx * map.cy;
  const double p = grid.pixel, p2 = p * p, full = static_cast<double>(S) * S;
  auto base = [&](int c) { return c >= 0 && c < cells && st.state_layer[c] == j && st.interface_weight[c] < 0.5; };
  const int neighbour[4] = {-1, 1, -map.cx, map.cx};
  LayerFigures f;
  for (int c : st.now) {
    const PhaseState::Counters& k = st.count[c];
    const double area = std::max(0.0, (full - k.kind[GridSupportSweep::kTrim]) * p2 - settings.xy_gap * k.kind[GridSupportSweep::kOutline] * p * kStaircase);
    const double w = st.interface_weight[c];
    f.base_area += (1.0 - w) * area;
    f.interface_area += w * area;
    if (k.kind[GridSupportSweep::kContact] > 0) f.contact_area += area;
    if (!base(c)) continue;
    if (settings.sheath) {
      f.outline += k.kind[GridSupportSweep::kOutline] * p * kStaircase;
      for (int s = 0; s < 4; ++s)
        if (!base(c + neighbour[s])) f.outline += (S - k.side_trimmed[s]) * p;
    }
    // The line on the boundary with the cell above, and at each of its ends half the link to the
    // line below (zigzag_link: the fill joins consecutive lines at alternate ends).
    const int up = c + map.cx;
    const bool line_up = base(up);
    if (line_up) f.fill_length += std::min(S - k.side_trimmed[3], S - st.count[up].side_trimmed[2]) * p;
    for (int side : {-1, 1}) {
      const bool end_up = line_up && !(base(c + side) && base(up + side));
      if (!end_up) continue;
      f.fill_length -= fill_end;
      f.fill_length += 0.5 * zigzag_link(st, map, base, c, side, S, p);
    }
  }
  f.fill_length = std::max(0.0, f.fill_length);
  return f;
}

}  // namespace

GridSweepResult GridSupportSweep::run(int ox, int oy) const {
  const int S = settings_.pixels_per_cell;
  if (ox < 0 || oy < 0 || ox >= S || oy >= S) throw std::invalid_argument("support sweep: phase offset outside the cell");
  const CellMap map(grid_, S, ox, oy);
  const int cells = map.cx * map.cy;
  PhaseState st(cells, S);
  const double p2 = grid_.pixel * grid_.pixel, full = static_cast<double>(S) * S;
  GridSweepResult out;
  out.layer.assign(static_cast<size_t>(layers_.count), 0.0);
  for (int j = top_layer_; j >= 0; --j) {
    for (int e = event_begin_[j]; e < event_begin_[j + 1]; ++e) st.apply(events_[e], map);
    const SweepRates& rate = rates_[j];
    // Columns at j: contacts here, and columns above whose projection passes.
    st.now.clear();
    double landing = 0.0;
    auto consider = [&](int c) {
      if (st.seen[c] == j) return;
      st.seen[c] = j;
      const bool above = st.column_above[c] != 0;
      if (above) landing += st.count[c].kind[kTop] * p2;
      // A contact in the first layer alone builds nothing: PrusaSlicer takes the first layer's
      // contacts out of its base and prints them nowhere (there is no raft to put them on).
      const bool contact = j > 0 && st.count[c].kind[kContact] > 0;
      if (!contact && !(above && st.count[c].kind[kBlock] < full)) return;
      st.now.push_back(c);
      if (st.count[c].kind[kDense] > 0) {
        st.dense_distance[c] = 0;
        st.dense_depth[c] = rate.interface_depth;
      } else {
        st.dense_distance[c] = above ? std::min(kNoDense, st.dense_distance[c] + 1) : kNoDense;
      }
      st.interface_weight[c] = std::clamp(st.dense_depth[c] - st.dense_distance[c], 0.0, 1.0);
      st.state_layer[c] = j;
    };
    for (int c : st.above) consider(c);
    size_t kept = 0;
    for (int c : st.contacts) {
      if (st.count[c].kind[kContact] <= 0) {
        st.listed_contact[c] = 0;
        continue;
      }
      st.contacts[kept++] = c;
      consider(c);
    }
    st.contacts.resize(kept);
    out.landing_area += landing;
    out.bottom_interface += landing * rate.bottom_interface_per_mm2;
    out.layer[j] += landing * rate.bottom_interface_per_mm2;
    const LayerFigures f = layer_figures(st, map, grid_, settings_, rate.fill_end, j);
    out.contact_area += f.contact_area;
    const double t = layers_.thickness(j);
    out.column_volume += t * (f.base_area + f.interface_area);
    if (j > 0) {
      const double fill = t * f.fill_length * rate.line_per_mm2;
      const double sheath = t * f.outline * rate.line_per_mm2, dense = t * f.interface_area * rate.interface_per_mm3;
      out.base_fill += fill;
      out.sheath += sheath;
      out.top_interface += dense;
      out.layer[j] += fill + sheath + dense;
    } else {
      // PrusaSlicer grows the first layer's base by first_layer_expansion and prints the interface
      // there (under a contact within its depth) as it is, without the growth: it takes the
      // interface out of the grown base.
      std::vector<int> base_cells, interface_cells;
      for (int c : st.now) (st.interface_weight[c] < 0.5 ? base_cells : interface_cells).push_back(c);
      const double dense = t * f.interface_area * rate.interface_per_mm3;
      out.top_interface += dense;
      out.first_layer = first_layer(base_cells, interface_cells, map.cx, ox, oy);
      out.layer[0] += out.first_layer + dense;
    }
    for (int c : st.above) st.column_above[c] = 0;
    for (int c : st.now) st.column_above[c] = 1;
    std::swap(st.above, st.now);
  }
  return out;
}

// The first layer: the base columns' free pixels grown by first_layer_expansion in steps that go
// around the part's first slice (alternately to the 4 and the 8 neighbours: an octagon), less the
// interface cells' pixels, filled at the first layer's density, with a sheath.
double GridSupportSweep::first_layer(const std::vector<int>& columns, const std::vector<int>& interface_cells, int cells_x,
                                     int ox, int oy) const {
  const int nx = grid_.nx, ny = grid_.ny, S = settings_.pixels_per_cell;
  const int steps = static_cast<int>(std::lround(settings_.first_layer_expansion / grid_.pixel));
  int i0 = nx, i1 = -1, j0 = ny, j1 = -1;
  for (int c : columns) {  // the pixels of cell c: i + S - ox in [ci·S, ci·S + S)
    const int ci = c % cells_x, cj = c / cells_x;
    i0 = std::min(i0, std::max(0, ci * S - S + ox)), i1 = std::max(i1, std::min(nx, ci * S + ox) - 1);
    j0 = std::min(j0, std::max(0, cj * S - S + oy)), j1 = std::max(j1, std::min(ny, cj * S + oy) - 1);
  }
  if (i1 < i0 || j1 < j0) return 0.0;
  // A window over the columns grown by the steps and one more pixel; outside the raster is
  // walled off. Codes: 0 free, 1 support, 2 the part's first slice, 3 outside.
  const int wi0 = i0 - steps - 1, wj0 = j0 - steps - 1, w = i1 - i0 + 2 * steps + 3, h = j1 - j0 + 2 * steps + 3;
  std::vector<std::uint8_t> code(static_cast<size_t>(w) * h, 3);
  for (int b = 0; b < h; ++b)
    for (int a = 0; a < w; ++a) {
      const int i = wi0 + a, j = wj0 + b;
      if (i >= 0 && j >= 0 && i < nx && j < ny) code[a + w * b] = solid_first_[i + nx * j] ? 2 : 0;
    }
  auto each_pixel = [&](int c, auto&& visit) {  // the window's pixels of cell c
    const int ci = c % cells_x, cj = c / cells_x;
    for (int j = std::max(wj0, std::max(0, cj * S - S + oy)); j < std::min(wj0 + h, std::min(ny, cj * S + oy)); ++j)
      for (int i = std::max(wi0, std::max(0, ci * S - S + ox)); i < std::min(wi0 + w, std::min(nx, ci * S + ox)); ++i)
        visit(i, j, (i - wi0) + w * (j - wj0));
  };
  for (int c : columns)
    each_pixel(c, [&](int i, int j, int q) {
      if (!trimmed_first_[i + nx * j]) code[q] = 1;
    });
  std::vector<std::uint8_t> interface(code.size(), 0);
  for (int c : interface_cells) each_pixel(c, [&](int, int, int q) { interface[q] = 1; });
  // Grown in steps to the 4 and then the 8 neighbours (an octagon), never into the part.
  std::vector<std::uint8_t> next;
  for (int step = 0; step < steps; ++step) {
    next = code;
    const bool diagonal = step % 2 == 1;
    for (int b = 1; b + 1 < h; ++b)
      for (int a = 1; a + 1 < w; ++a) {
        const int q = a + w * b;
        if (code[q] != 0) continue;
        bool reached = code[q - 1] == 1 || code[q + 1] == 1 || code[q - w] == 1 || code[q + w] == 1;
        if (diagonal) reached = reached || code[q - w - 1] == 1 || code[q - w + 1] == 1 || code[q + w - 1] == 1 || code[q + w + 1] == 1;
        if (reached) next[q] = 1;
      }
    code.swap(next);
  }
  double area = 0.0, outline = 0.0, along_part = 0.0;
  for (int b = 1; b + 1 < h; ++b)
    for (int a = 1; a + 1 < w; ++a) {
      const int q = a + w * b;
      if (code[q] != 1 || interface[q]) continue;
      area += 1.0;
      for (int r : {q - 1, q + 1, q - w, q + w}) {
        if (code[r] == 1 && !interface[r]) continue;
        outline += 1.0;
        along_part += code[r] == 2;
      }
    }
  const double p = grid_.pixel;
  area = std::max(0.0, area * p * p - settings_.xy_gap * along_part * p * kStaircase);
  outline *= p * kStaircase;
  const SweepRates& rate = rates_[0];
  return rate.first_fill_per_mm2 * std::max(0.0, area - rate.first_inset * outline) + rate.first_sheath_per_mm * outline;
}

}  // namespace slim
