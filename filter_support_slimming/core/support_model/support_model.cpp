#include "core/support_model/support_model.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"
#include "core/print/rotation_to_up.h"
#include "core/support_model/support_raster.h"
#include "core/support_model/support_sweep.h"

namespace slim {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("support model: " + what);
}

void check_options(const SupportModelOptions& o) {
  require(o.print.direction.allFinite() && o.print.direction.norm() > 0, "the print direction must be a non-zero vector");
  require(o.print.alpha_max_deg > 0 && o.print.alpha_max_deg < 90, "alpha_max must lie strictly between 0 and 90 degrees");
  require(o.threshold_slack_deg >= 0 && o.threshold_slack_deg < 10, "the threshold slack must lie in [0, 10) degrees");
  require(o.layer_height > 0 && o.first_layer_height > 0 && o.max_support_layer_height >= o.layer_height,
          "layer heights must be positive, the support's at least the object's");
  require(o.nozzle_diameter > 0 && o.extrusion_width > 0, "nozzle and extrusion width must be positive");
  require(o.extrusion_width > o.max_support_layer_height * (1 - M_PI / 4) && o.extrusion_width > o.first_layer_height * (1 - M_PI / 4),
          "the extrusion width is too small for the layer height");
  require(o.grid_spacing > o.extrusion_width, "the grid spacing must exceed the extrusion width");
  require(o.contact_distance >= 0 && o.xy_gap >= 0 && o.dense_interface_overhang > 0, "gaps must not be negative");
  require(o.interface_layers >= 0 && o.interface_layers <= 100, "interface layers must lie in [0, 100]");
  require(o.first_layer_density >= 0 && o.first_layer_density <= 1, "the first layer density must lie in [0, 1]");
  require(o.first_layer_expansion >= 0 && o.first_layer_expansion < 100, "the first layer expansion must lie in [0, 100) mm");
  require(o.pixels_per_cell >= 1 && o.pixels_per_cell <= 32, "pixels per cell must lie in [1, 32]");
  const int n = o.pixels_per_cell;
  require(o.grid_phases == 1 || o.grid_phases == n || o.grid_phases == n * n, "grid phases must be 1, pixels_per_cell or its square");
  require(o.turns >= 1 && o.turns <= 90, "turns must lie in [1, 90]");
  require(o.slice_max_gap >= 0 && o.slice_max_gap < 1000, "the slice gap to close must lie in [0, 1000) mm");
}

GridSweepSettings sweep_settings(const SupportModelOptions& o) {
  GridSweepSettings s;
  s.pixels_per_cell = o.pixels_per_cell;
  s.contact_distance = o.contact_distance;
  s.xy_gap = o.xy_gap;
  s.grid_spacing = o.grid_spacing;
  s.extrusion_width = o.extrusion_width;
  s.nozzle_diameter = o.nozzle_diameter;
  s.max_support_layer_height = o.max_support_layer_height;
  s.interface_layers = o.interface_layers;
  s.sheath = o.sheath;
  s.first_layer_density = o.first_layer_density;
  s.first_layer_expansion = o.first_layer_expansion;
  return s;
}

// Cell offsets (in pixels) of the phases averaged: k/n of a cell along x, a permutation along y
// (so the n phases cover every row and column once), or every pixel offset.
std::vector<std::pair<int, int>> phase_offsets(int per_cell, int phases) {
  std::vector<std::pair<int, int>> out;
  if (phases == 1) out.push_back({0, 0});
  else if (phases == per_cell)
    for (int k = 0; k < per_cell; ++k) out.push_back({k, (k * (per_cell - 1)) % per_cell});
  else
    for (int k = 0; k < per_cell * per_cell; ++k) out.push_back({k % per_cell, k / per_cell});
  return out;
}

// Whether the enclosed volume of positions V with faces F is negative: signed_volume()'s terms,
// summed in blocks on the threads (every estimate asks, and signed_volume() is one serial pass;
// only the sign is read, which no order of the sum changes but for a part of no volume).
bool negative_volume(const Points& V, const Triangles& F) {
  const Eigen::RowVector3d centre = V.colwise().mean();
  const Eigen::Index faces = F.rows(), block = 1 << 16;
  std::vector<double> part(static_cast<size_t>((faces + block - 1) / block), 0.0);
  parallel_for(static_cast<int>(part.size()), [&](int b) {
    for (Eigen::Index f = b * block; f < std::min(faces, (b + 1) * block); ++f) {
      const Eigen::Vector3d a = (V.row(F(f, 0)) - centre).transpose(), p = (V.row(F(f, 1)) - centre).transpose(),
                            c = (V.row(F(f, 2)) - centre).transpose();
      part[static_cast<size_t>(b)] += a.dot(p.cross(c));
    }
  });
  double volume = 0.0;
  for (double v : part) volume += v;
  return volume < 0.0;
}

// The part in the print frame, kept from estimate to estimate: a fresh copy of the positions and
// the faces costs a page fault every 4 kB, a large share of an estimate on a large part.
struct PrintFrame {
  Surface part;         // its faces: the estimate's, or those turned over (turned)
  bool turned = false;
  // The adjacency of the faces turned over, made the first time a pose needs it: the raster reads
  // edge k of face f as the frame's faces run, and turning a face over renumbers its edges.
  std::unique_ptr<FaceAdjacency> turned_adjacency;
  const FaceAdjacency& adjacency(const FaceAdjacency& as_given) {
    if (!turned) return as_given;
    if (!turned_adjacency)
      turned_adjacency = std::make_unique<FaceAdjacency>(part.F, part.V.rows(), as_given.has_every_twin());
    return *turned_adjacency;
  }
};

// Positions V (faces F) into `frame`: turned about +Z, resting on z = 0; the faces turned over
// when the enclosed volume is negative (an inside-out part).
void print_frame(const Points& V, const Triangles& F, const SupportModelOptions& o, double turn, PrintFrame& frame) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                            rotation_to_up(unit_print_direction(o.print.direction));
  frame.part.V.resize(V.rows(), 3);
  frame.part.V.noalias() = V * r.transpose();
  const double plate = frame.part.V.col(2).minCoeff();
  frame.part.V.col(2).array() -= plate;
  if (frame.part.F.rows() != F.rows()) {
    frame.part.F = F;
    frame.turned = false;
  }
  const bool turn_over = negative_volume(frame.part.V, F);
  if (turn_over != frame.turned) frame.part.F.col(1).swap(frame.part.F.col(2));
  frame.turned = turn_over;
}

constexpr double kMaxLayers = 50000.0, kMaxCellLayers = 1e9;

PixelGrid raster_grid(const Surface& s, const SupportModelOptions& o) {
  const Eigen::Vector3d lo = s.V.colwise().minCoeff(), hi = s.V.colwise().maxCoeff();
  const double cell = o.grid_spacing, margin = o.first_layer_expansion + 2.0 * cell;
  const Eigen::Vector2d centre = 0.5 * (lo + hi).head<2>();
  PixelGrid g;
  g.pixel = cell / o.pixels_per_cell;
  const double below_x = std::ceil((centre.x() - lo.x() + margin) / cell), below_y = std::ceil((centre.y() - lo.y() + margin) / cell);
  const double above_x = std::ceil((hi.x() - centre.x() + margin) / cell), above_y = std::ceil((hi.y() - centre.y() + margin) / cell);
  require(below_x + above_x < 4096 && below_y + above_y < 4096, "the part is too large for the grid (over 4096 cells across)");
  g.x0 = centre.x() - below_x * cell;
  g.y0 = centre.y() - below_y * cell;
  g.nx = static_cast<int>(below_x + above_x) * o.pixels_per_cell;
  g.ny = static_cast<int>(below_y + above_y) * o.pixels_per_cell;
  return g;
}

// What every estimate checks first: the options, the positions (finite) and the faces (some, and
// indices within the positions; a SupportModel checked them once).
void check_input(const Points& V, const Triangles& F, const SupportModelOptions& o, bool faces_checked) {
  check_options(o);
  if (!faces_checked || !V.allFinite()) check_surface(Surface{V, faces_checked ? Triangles() : F});
  require(F.rows() > 0, "the surface has no faces");
}

// Whether some edge of the faces is used by one face only: a hole, which the slicer's slices read
// otherwise than rays do.
bool has_open_edges(const Triangles& faces, Eigen::Index vertices) {
  return edge_topology(Surface{Points::Zero(vertices, 3), faces}).open_edges > 0;
}

// The estimate of a surface whose options and faces the caller has checked (check_input).
SupportEstimate estimate_with(const Points& V, const Triangles& F, const FaceAdjacency& adjacency, bool open,
                              const SupportModelOptions& o, PrintFrame& print) {
  const auto offsets = phase_offsets(o.pixels_per_cell, o.grid_phases);
  const GridSweepSettings settings = sweep_settings(o);
  OverhangRule rule;
  rule.max_slope_deg = 90.0 - o.print.alpha_max_deg + o.threshold_slack_deg;
  rule.dense_slope_deg = std::atan(o.layer_height / o.dense_interface_overhang) * 180.0 / M_PI;
  rule.layer_height = o.layer_height;
  rule.first_layer_height = o.first_layer_height;
  rule.creases = o.bottom_creases;
  rule.tips = o.lowest_points;
  rule.slices = open && o.open_mesh_slices;
  rule.slice_max_gap = o.slice_max_gap;
  const ThreadScope threads(o.threads);
  SupportEstimate est;
  std::vector<GridSweepResult> runs;
  for (int t = 0; t < o.turns; ++t) {
    print_frame(V, F, o, M_PI * t / o.turns, print);
    const Surface& frame = print.part;
    const double height = frame.V.col(2).maxCoeff();
    require(height > 0, "the part has no height along the print direction");
    SlicerLayers layers;
    layers.first_height = o.first_layer_height;
    layers.height = o.layer_height;
    // A part far larger than any printer would take hours to sweep: refused (the optimizer and
    // the orientation search then judge it by their cruder estimates).
    const double layer_count = std::ceil(std::max(0.0, height - o.first_layer_height) / o.layer_height) + 2;
    require(layer_count <= kMaxLayers, "the part is too tall for the support model (more than 50,000 slicer layers)");
    layers.count = static_cast<int>(layer_count);
    const PixelGrid grid = raster_grid(frame, o);
    const double cells = static_cast<double>(grid.nx / o.pixels_per_cell) * (grid.ny / o.pixels_per_cell);
    require(cells * layer_count <= kMaxCellLayers, "the part is too large for the support model (more than 1e9 grid cells times layers)");
    const SupportRaster raster = build_support_raster(frame, print.adjacency(adjacency), grid, rule);
    const GridSupportSweep sweep(raster, layers, settings);
    std::vector<GridSweepResult> phase(offsets.size());
    parallel_for(static_cast<int>(offsets.size()), [&](int k) { phase[k] = sweep.run(offsets[k].first, offsets[k].second); });
    runs.insert(runs.end(), phase.begin(), phase.end());
    est.pixel_mm = grid.pixel;
    est.layers = layers.count;
    est.cells = (grid.nx / o.pixels_per_cell) * (grid.ny / o.pixels_per_cell);
  }
  const double n = static_cast<double>(runs.size());
  est.min_phase_mm3 = INFINITY;
  est.max_phase_mm3 = -INFINITY;
  for (const GridSweepResult& r : runs) {
    est.base_fill_mm3 += r.base_fill / n;
    est.sheath_mm3 += r.sheath / n;
    est.top_interface_mm3 += r.top_interface / n;
    est.bottom_interface_mm3 += r.bottom_interface / n;
    est.first_layer_mm3 += r.first_layer / n;
    est.contact_area_mm2 += r.contact_area / n;
    est.landing_area_mm2 += r.landing_area / n;
    est.column_volume_mm3 += r.column_volume / n;
    est.phase_mm3.push_back(r.total());
    if (est.layer_mm3.size() < r.layer.size()) est.layer_mm3.resize(r.layer.size(), 0.0);
    for (size_t j = 0; j < r.layer.size(); ++j) est.layer_mm3[j] += r.layer[j] / n;
    est.min_phase_mm3 = std::min(est.min_phase_mm3, r.total());
    est.max_phase_mm3 = std::max(est.max_phase_mm3, r.total());
  }
  est.volume_mm3 = est.base_fill_mm3 + est.sheath_mm3 + est.top_interface_mm3 + est.bottom_interface_mm3 + est.first_layer_mm3;
  return est;
}

}  // namespace

struct SupportModel::Impl {
  Triangles F;
  Eigen::Index vertices;
  FaceAdjacency adjacency;
  bool open;
  PrintFrame frame;  // estimate()'s buffers
  Impl(const Triangles& faces, Eigen::Index n)
      : F(checked_faces(faces, n)), vertices(n), adjacency(faces, n, true), open(has_open_edges(faces, n)) {}
  // The faces' indices checked before the adjacency reads them (positions come later).
  static const Triangles& checked_faces(const Triangles& faces, Eigen::Index n) {
    check_surface(Surface{Points::Zero(n, 3), faces});
    return faces;
  }
};

SupportModel::SupportModel(const Triangles& faces, Eigen::Index vertices)
    : impl_(std::make_unique<Impl>(faces, vertices)) {}
SupportModel::~SupportModel() = default;
SupportModel::SupportModel(SupportModel&&) noexcept = default;

SupportEstimate SupportModel::estimate(const Points& V, const SupportModelOptions& o) {
  require(V.rows() == impl_->vertices, "the positions have " + std::to_string(V.rows()) + " rows for a mesh of " +
                                           std::to_string(impl_->vertices) + " vertices");
  check_input(V, impl_->F, o, true);
  return estimate_with(V, impl_->F, impl_->adjacency, impl_->open, o, impl_->frame);
}

SupportEstimate estimate_support(const Surface& surface, const SupportModelOptions& o) {
  check_input(surface.V, surface.F, o, false);
  PrintFrame frame;
  return estimate_with(surface.V, surface.F, FaceAdjacency(surface), has_open_edges(surface.F, surface.V.rows()), o, frame);
}

}  // namespace slim
