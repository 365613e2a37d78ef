#include "support/bad_inputs.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/geometry/welded_view.h"
#include "core/print/overhang.h"
#include "support/shapes.h"

namespace slim::test {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Surface with_vertices(const Surface& s, const std::vector<Eigen::Vector3d>& extra) {
  Surface out = s;
  out.V.conservativeResize(s.V.rows() + static_cast<Eigen::Index>(extra.size()), 3);
  for (size_t i = 0; i < extra.size(); ++i) out.V.row(s.V.rows() + static_cast<Eigen::Index>(i)) = extra[i].transpose();
  return out;
}

Surface with_faces(const Surface& s, const std::vector<Eigen::Vector3i>& extra) {
  Surface out = s;
  out.F.conservativeResize(s.F.rows() + static_cast<Eigen::Index>(extra.size()), 3);
  for (size_t i = 0; i < extra.size(); ++i) out.F.row(s.F.rows() + static_cast<Eigen::Index>(i)) = extra[i].transpose();
  return out;
}

Surface without_faces(const Surface& s, const std::vector<int>& drop) {
  Surface out;
  out.V = s.V;
  out.F.resize(s.F.rows() - static_cast<Eigen::Index>(drop.size()), 3);
  Eigen::Index n = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (std::find(drop.begin(), drop.end(), static_cast<int>(f)) == drop.end()) out.F.row(n++) = s.F.row(f);
  return out;
}

// The faces of `s` whose normal is close to `n` (the T's bar top: +Z, above the stem's top).
std::vector<int> faces_facing(const Surface& s, const Eigen::Vector3d& n, double min_height) {
  const Points normals = face_normals(s);
  std::vector<int> out;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (normals.row(f).dot(n) > 0.99 && s.V(s.F(f, 0), 2) > min_height) out.push_back(static_cast<int>(f));
  return out;
}

BadInput valid(std::string name, std::string what, Surface s) {
  BadInput c;
  c.name = std::move(name);
  c.what = std::move(what);
  c.surface = std::move(s);
  return c;
}

BadInput refused(std::string name, std::string what, Surface s, std::string refusal, std::string advice) {
  BadInput c = valid(std::move(name), std::move(what), std::move(s));
  c.refusal = std::move(refusal);
  c.advice = std::move(advice);
  return c;
}

}  // namespace

bool mentions(const std::string& text, const std::string& part) {
  auto lower = [](std::string x) {
    for (char& ch : x) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return x;
  };
  return lower(text).find(lower(part)) != std::string::npos;
}

std::vector<BadInput> bad_inputs() {
  const Surface T = t_shape();
  const double t_risky = t_shape_arm_underside_area();
  std::vector<BadInput> cases;
  auto add = [&](BadInput c) -> BadInput& {
    cases.push_back(std::move(c));
    return cases.back();
  };

  // ---- the mesh itself ---------------------------------------------------------------------------
  {
    BadInput& c = add(refused("empty_mesh", "no vertices, no faces", Surface{Points(0, 3), Triangles(0, 3)}, "no faces",
                              "triangle mesh"));
    c.analysis_refusal = "no faces";
  }
  {
    BadInput& c = add(refused("vertices_only", "three vertices and no face (a point cloud)",
                              with_vertices(Surface{Points(0, 3), Triangles(0, 3)}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}),
                              "no faces", "triangle mesh"));
    c.analysis_refusal = "no faces";
    c.meshlabserver = true;
  }
  add(valid("single_triangle", "one triangle leaning out over the plate",
            triangle({0, 0, 0}, {0, 10, 0}, {10, 0, 5})))
      .meshlabserver = true;
  {
    // A sliver with three collinear corners, a face with a repeated vertex, on the T.
    Surface s = with_vertices(T, {(T.V.row(T.F(0, 0)) + T.V.row(T.F(0, 1))).transpose() / 2.0});
    const int mid = static_cast<int>(s.V.rows()) - 1;
    s = with_faces(s, {{T.F(0, 0), mid, T.F(0, 1)}, {T.F(1, 0), T.F(1, 0), T.F(1, 1)}});
    BadInput& c = add(valid("degenerate_faces", "the T plus a zero-area sliver and a face with a repeated vertex", s));
    c.risky_before = t_risky;
  }
  add(refused("coincident_vertices", "three faces whose vertices all sit on one point",
              with_faces(with_vertices(Surface{Points(0, 3), Triangles(0, 3)}, {{5, 5, 5}, {5, 5, 5}, {5, 5, 5}}),
                         {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}}),
              "zero extent", "check the file"));
  {
    // A CAD sliver: a needle triangle 40 mm long and 1e-12 mm wide inside the bar (clipping it
    // against the tets loses a share of its area to rounding).
    const int n = static_cast<int>(T.V.rows());
    const Surface s = with_faces(with_vertices(T, {{-20, 1, 23}, {20, 1, 23}, {20.0 / 3.0, 1 + 1e-12, 23}}), {{n, n + 1, n + 2}});
    add(valid("needle_face", "the T plus a needle triangle 1e-12 mm wide", s)).risky_before = t_risky;
  }
  {
    // Every face twice, and one face moved onto a copy of its first vertex (a seam).
    Surface twice = with_vertices(T, {T.V.row(T.F(0, 0)).transpose()});
    twice.F.resize(2 * T.F.rows(), 3);
    twice.F << T.F, T.F;
    twice.F(0, 0) = static_cast<int>(twice.V.rows()) - 1;
    add(valid("duplicate_vertices_and_faces", "the T with every face twice and a duplicated vertex", twice));
  }
  {
    const Surface s = with_vertices(T, {{0, 0, 10}, {30, 0, 3}});
    BadInput& c = add(valid("unreferenced_vertices", "the T plus a vertex inside it and one beside it, in no face", s));
    c.risky_before = t_risky;
    BadInput& t = add(refused("unreferenced_vertices_tetgen", "the same with the TetGen domain", s, "belongs to no face",
                              "remove the unreferenced vertices"));
    t.options.domain = DomainKind::TetGen;
  }
  {
    Surface s = T;
    s.V(3, 0) = kNaN;
    BadInput& c = add(refused("nan_coordinate", "the T with one NaN coordinate", s, "NaN", "repair or remove"));
    c.analysis_refusal = "NaN";
    c.meshlabserver = true;
    s = T;
    s.V(5, 2) = kInf;
    add(refused("inf_coordinate", "the T with one infinite coordinate", s, "infinite", "repair or remove"))
        .analysis_refusal = "infinite";
    add(refused("nan_unreferenced_vertex", "the T plus a NaN vertex that no face uses", with_vertices(T, {{kNaN, 0, 0}}),
                "NaN", "unreferenced"))
        .analysis_refusal = "NaN";
  }
  // The T with the top of its bar cut away: open, the arm undersides still overhang.
  const Surface open_t = without_faces(T, faces_facing(T, Eigen::Vector3d::UnitZ(), 21.0));
  add(valid("open_mesh", "the T with the top of its bar removed (a hole)", open_t)).risky_before = t_risky;
  {
    const Surface edge = weld(merge(box({0, 0, 0}, {10, 10, 10}), box({10, 0, 10}, {20, 10, 20})));
    BadInput& c = add(valid("nonmanifold_edge", "two boxes sharing one edge, the upper one overhanging", edge));
    c.risky_before = 100.0;
    c.meshlabserver = true;
    add(refused("nonmanifold_edge_tetgen", "the same with the TetGen domain", edge, "not manifold", "voxel domain"))
        .options.domain = DomainKind::TetGen;
    const Surface vertex = weld(merge(box({0, 0, 0}, {10, 10, 10}), box({10, 10, 10}, {20, 20, 20})));
    add(valid("nonmanifold_vertex", "two boxes sharing one corner, the upper one floating", vertex)).risky_before = 100.0;
    // Every edge has two faces and no faces cross, so TetGen gets it, and meshes it.
    BadInput& t = add(valid("nonmanifold_vertex_tetgen", "the same with the TetGen domain", vertex));
    t.options.domain = DomainKind::TetGen;
    t.risky_before = 100.0;
  }
  {
    const Surface s = merge(merge(T, box({30, -5, 30}, {40, 5, 35})), box({-40, -5, 0}, {-30, 5, 10}));
    BadInput& c = add(valid("several_components", "the T, a floating box and a box on the plate", s));
    c.risky_before = t_risky + 100.0;
    c.meshlabserver = true;
  }
  {
    Surface s = T;
    s.F.row(0) = Eigen::RowVector3i(T.F(0, 0), T.F(0, 2), T.F(0, 1));
    BadInput& c = add(refused("inconsistent_orientation", "the T with one face turned over", s,
                              "not consistently oriented", "re-orient"));
    c.meshlabserver = true;
  }
  {
    BadInput& c = add(valid("inside_out", "the T with every face turned over (negative volume)", flipped(T)));
    c.inside_out = true;
    c.risky_before = t_risky;
    c.meshlabserver = true;
  }
  {
    const Surface s = merge(box({0, 0, 0}, {10, 10, 10}), box({5, 0, 5}, {25, 10, 15}));
    add(valid("self_intersecting", "two boxes that overlap, faces crossing faces", s));
    BadInput& c = add(refused("self_intersecting_tetgen", "the same with the TetGen domain", s, "intersects itself",
                              "voxel domain"));
    c.options.domain = DomainKind::TetGen;
    c.meshlabserver = true;
  }
  add(valid("tetgen_clean", "the T with the TetGen domain (clean and closed)", T)).options.domain = DomainKind::TetGen;

  // ---- scale and position -------------------------------------------------------------------------
  {
    BadInput& c = add(valid("huge_model", "the T scaled to 1e6 mm", transformed(T, 2e4 * Eigen::Matrix3d::Identity())));
    c.risky_before = t_risky * 4e8;
    c.meshlabserver = true;
    BadInput& d = add(valid("tiny_model", "the T scaled to 1e-3 mm", transformed(T, 2e-5 * Eigen::Matrix3d::Identity())));
    d.risky_before = t_risky * 4e-10;
    d.meshlabserver = true;
    BadInput& e = add(valid("far_from_origin", "the T moved to (1e5, -1e5, 1e5) mm",
                            transformed(T, Eigen::Matrix3d::Identity(), {1e5, -1e5, 1e5})));
    e.risky_before = t_risky;
    e.meshlabserver = true;
  }

  // ---- the settings --------------------------------------------------------------------------------
  auto setting = [&](BadInput c, auto&& set) -> BadInput& {
    set(c.options);
    return add(std::move(c));
  };
  setting(refused("print_direction_zero", "print direction (0, 0, 0)", T, "print direction", "non-zero"),
          [](SlimmingOptions& o) { o.print.direction = Eigen::Vector3d::Zero(); })
      .analysis_refusal = "print direction";
  cases.back().meshlabserver = true;
  setting(refused("print_direction_nan", "print direction (NaN, 0, 1)", T, "print direction", "non-zero"),
          [](SlimmingOptions& o) { o.print.direction = Eigen::Vector3d(kNaN, 0, 1); })
      .analysis_refusal = "print direction";
  setting(valid("print_direction_non_unit", "print direction (0, 0, 7)", T),
          [](SlimmingOptions& o) { o.print.direction = Eigen::Vector3d(0, 0, 7); })
      .risky_before = t_risky;
  setting(refused("alpha_negative", "self-supporting angle -5 deg", T, "self-supporting angle", "[0, 90)"),
          [](SlimmingOptions& o) { o.print.alpha_max_deg = -5; })
      .analysis_refusal = "[0, 90)";
  setting(refused("alpha_90", "self-supporting angle 90 deg", T, "self-supporting angle", "[0, 90)"),
          [](SlimmingOptions& o) { o.print.alpha_max_deg = 90; })
      .analysis_refusal = "[0, 90)";
  cases.back().meshlabserver = true;
  setting(refused("alpha_nan", "self-supporting angle NaN", T, "self-supporting angle", "[0, 90)"),
          [](SlimmingOptions& o) { o.print.alpha_max_deg = kNaN; })
      .analysis_refusal = "[0, 90)";
  setting(valid("iterations_zero", "iteration limit 0: embed and write back", T),
          [](SlimmingOptions& o) { o.steps.max_iterations = 0; })
      .meshlabserver = true;
  setting(refused("iterations_negative", "iteration limit -1", T, "iteration limit", "0 or more"),
          [](SlimmingOptions& o) { o.steps.max_iterations = -1; });
  setting(valid("resolution_one", "voxel resolution 1", T), [](SlimmingOptions& o) { o.resolution = 1; })
      .risky_before = t_risky;
  setting(refused("resolution_zero", "voxel resolution 0", T, "voxel resolution", "at least 1"),
          [](SlimmingOptions& o) { o.resolution = 0; });
  setting(refused("resolution_absurd", "voxel resolution 1,000,000 (the memory guard)", T, "voxel resolution",
                  "at most"),
          [](SlimmingOptions& o) { o.resolution = 1000000; })
      .meshlabserver = true;
  setting(refused("max_k_zero", "at most 0 K-means proxies", T, "proxies", "at least 1"),
          [](SlimmingOptions& o) { o.steps.max_k = 0; });
  setting(refused("deviation_nan", "deviation budget NaN %", T, "deviation budget", "finite"),
          [](SlimmingOptions& o) { o.budget = DeviationBudget::from_percent(kNaN); });
  setting(valid("deviation_none", "deviation budget 0 (none)", T), [](SlimmingOptions& o) { o.budget = DeviationBudget::from_percent(0); });
  setting(valid("paper_method", "the paper's method on the open T", open_t),
          [](SlimmingOptions& o) { o.method = SlimmingMethod::Paper; });

  // ---- what is risky, and the selection --------------------------------------------------------------
  {
    const Surface bowl = open_hemisphere(2, 10.0, true);
    BadInput& c = setting(valid("every_face_risky", "an open bowl, every face overhanging at 0 deg", bowl),
                          [](SlimmingOptions& o) { o.print.alpha_max_deg = 0; });
    c.risky_before = face_areas(bowl).sum();
    add(valid("no_face_risky", "a box: nothing overhangs", box({0, 0, 0}, {10, 10, 10}))).risky_before = 0.0;
  }
  {
    BadInput& c = add(valid("empty_selection_rigid", "rigid features on, no face selected", T));
    c.preserve_selection = true;
    c.options.rigid_features.assign(static_cast<size_t>(T.F.rows()), false);
    c.plugin_refusal = "no face is selected";
    BadInput& all = add(valid("selection_everything", "rigid features on, every face selected", T));
    all.preserve_selection = true;
    all.options.rigid_features.assign(static_cast<size_t>(T.F.rows()), true);
    all.risky_before = t_risky;
  }
  return cases;
}

void write_ascii_ply(const std::string& path, const Surface& s) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fprintf(f, "ply\nformat ascii 1.0\nelement vertex %ld\nproperty float x\nproperty float y\nproperty float z\n",
               static_cast<long>(s.V.rows()));
  std::fprintf(f, "element face %ld\nproperty list uchar int vertex_indices\nend_header\n", static_cast<long>(s.F.rows()));
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) std::fprintf(f, "%.9g %.9g %.9g\n", s.V(v, 0), s.V(v, 1), s.V(v, 2));
  for (Eigen::Index t = 0; t < s.F.rows(); ++t) std::fprintf(f, "3 %d %d %d\n", s.F(t, 0), s.F(t, 1), s.F(t, 2));
  std::fclose(f);
}

void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name << " (" << c.what << ")"; }

std::string slimming_result_problem(const Surface& input, const SlimmingOptions& o, const SlimmingResult& r) {
  std::ostringstream why;
  const Surface& out = r.surface;
  if (out.V.rows() != input.V.rows() || out.F != input.F) return "the result's topology differs from the input's";
  if (!out.V.allFinite()) return "the result has a non-finite vertex";
  if (r.displacement.size() != input.V.rows() || !r.displacement.allFinite()) return "bad displacement vector";
  const double diag = (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm();
  const double moved_err = (r.displacement - (out.V - input.V).rowwise().norm()).cwiseAbs().maxCoeff();
  if (moved_err > 1e-9 * diag) why << "displacements differ from the positions by " << moved_err << "; ";

  const Eigen::Vector3d d = o.print.direction.normalized();
  const double plate = (input.V * d).minCoeff(), lowest = (out.V * d).minCoeff();
  if (lowest < plate - 1e-9 * diag) why << "a vertex went " << plate - lowest << " below the plate; ";
  if (o.budget.share_percent().value_or(0.0) > 0.0) {
    // The surface follows the domain through barycentric sums, exact to a few ulps of the
    // coordinates: a budget below that (1e-38 %) is kept only to that rounding.
    const double budget = o.budget.share_percent().value_or(0.0) / 100.0 * diag;
    const double rounding = 16 * std::numeric_limits<double>::epsilon() * input.V.cwiseAbs().maxCoeff();
    if (r.displacement.maxCoeff() > budget * (1.0 + 1e-9) + rounding)
      why << "a vertex moved " << r.displacement.maxCoeff() << ", over the budget " << budget << "; ";
  }
  if (r.iterations > o.steps.max_iterations) why << "more iterations than allowed; ";

  // The statistics re-measure, on the part the run saw (turned over when inside out).
  PrintSetup measure;
  measure.direction = d;
  measure.alpha_max_deg = o.print.alpha_max_deg;
  const std::optional<double> tolerance = o.print.plate.tolerance_mm(diag);  // the input's, as the run's
  measure.plate = tolerance ? PlateRule::within(*tolerance) : PlateRule::none();
  const Surface seen = r.inside_out ? flipped(out) : out;
  const OverhangReport now = analyse_overhang(seen, measure);
  const double slack = 1e-6 * now.total_area;
  if (std::abs(now.risky_area - r.after.risky_area) > slack)
    why << "the reported risky area " << r.after.risky_area << " re-measures as " << now.risky_area << "; ";
  if (r.after.risky_area > r.before.risky_area + slack)
    why << "the risky area grew from " << r.before.risky_area << " to " << r.after.risky_area << "; ";
  if (!std::isfinite(r.shape.volume_input) || !std::isfinite(r.shape.volume_result)) why << "non-finite volume; ";
  for (const IterationStats& st : r.history)
    if (!std::isfinite(st.risky_area) || !std::isfinite(st.energy) || !std::isfinite(st.max_displacement) ||
        !std::isfinite(st.approximation_error))
      why << "non-finite statistics in iteration " << st.iteration << "; ";
  return why.str();
}

OrientationResult fast_orientation(const Surface& s, double alpha_max_deg, std::string& refusal) {
  OrientationOptions o = with_effort(OrientationEffort::Fast);
  o.alpha_max_deg = static_cast<float>(alpha_max_deg);  // the filter's parameter is a float
  refusal.clear();
  const WeldedView view = weld_coincident(s);  // the filter computes on the welded view
  try {
    return optimize_orientation(view.surface, o);
  } catch (const std::invalid_argument& e) {
    refusal = e.what() + view.vertex_number_note(e.what());
    return {};
  }
}

}  // namespace slim::test
