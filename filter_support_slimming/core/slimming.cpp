#include "core/slimming.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/arap.h"
#include "core/axis_rotation.h"
#include "core/embedding.h"
#include "core/overhang_boundary.h"
#include "core/parallel_for.h"
#include "core/polar.h"
#include "core/proxy_rotation.h"
#include "core/tetgen_domain.h"
#include "core/voxel_domain.h"

// Choices the paper leaves open (documented in slimming.h and README):
//  * Which faces constrain a tet: every non-plate face piece in it (the paper's P), not only the
//    risky ones, so a rotation that fixes one face never breaks a safe neighbour.
//  * Margin: the local step solves for alpha_max - margin and every measurement uses alpha_max.
//  * Step cap: each tet's extra rotation is at most max_step_deg per iteration, so the global
//    step is never asked for a jump it can only half follow.
//  * Straight-down faces: the tie between equally near rotations is broken towards the horizontal
//    direction from the part's vertical axis to the tet, so the two arms of a T or the rim of a
//    mushroom cap all bend up and outwards together (paper Fig. 8 is what happens otherwise).
//    The coherent method breaks it towards the overhang's nearest edge instead (below).
//  * Deviation budget: each domain vertex's displacement from rest is projected onto the budget
//    ball after every global step (the overshooting part of the step is rolled back). Surface
//    vertices are convex combinations of domain vertices, so the surface cannot overshoot either.
//  * Inversion guard (the paper's method): a step that would invert a tet is cut back to the
//    largest fraction that keeps every tet positive, and the run stops there.
//  * Output: the best iterate by estimated support, the shadow volume (overhang.h), among those
//    with no more risky area than the input: bending a T's arms or a mushroom's rim can shrink
//    the risky area while the overhangs left move higher and need more support. When no iterate
//    beats the input, the input returns.
//
// What SlimmingMethod::Coherent adds to the paper (each measured, see README):
//  * risky_boost: tets holding faces that are risky at the start weigh more in the global step, so
//    their rotations are carried out instead of being averaged away by the stiff volume;
//  * interior_weight: tets holding no surface face get this share of their volume weight, so the
//    surface leads and the interior follows instead of holding it back;
//  * rotation smoothing: each risky tet's extra rotation is blended with those of its
//    face-neighbouring risky tets (area-weighted quaternion average), so neighbours turn together;
//  * propagation: safe tets next to risky ones take a share of their neighbours' extra rotation,
//    so a region turns as a body rather than as a skin;
//  * edge turns: a tet holding a flat overhang (a risky face nearly straight down) turns about
//    the horizontal axis that tilts it towards the nearest edge of the input's flat overhang
//    region (overhang_boundary.h, axis_rotation.h), as long as that costs little more than its
//    minimal turn; straight-down faces break their tie that way too. A flat overhang then grows a
//    bevel or keel along its edges, which a small budget can reach, instead of tilting as a whole
//    about the part's axis or its outer rim, which it cannot. The region is the flat faces only,
//    not all risky ones: the flat crown of an arch turns towards the curved overhang around it
//    (a pointed arch), not towards the arch's front and back;
//  * local inversion guard: the vertices of the tets a step would invert are rolled back to
//    where they were (the set grows until nothing inverts) and the run goes on, instead of the
//    whole step being cut back and the run stopped where the first tet would have inverted.

namespace slim {
namespace {

// Adds the time since construction to a counter when it goes out of scope.
class StageTimer {
 public:
  explicit StageTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

// Measured with bench/slimming_curve on the bunny, T, mushroom and arch (README has the table).
// The weights are fixed before the one factorization, so they use the input's risky faces.
struct CoherentSettings {
  double interior_weight = 0.1;  // weight factor for tets that hold no surface face
  double risky_boost = 10.0;     // weight factor for tets that hold risky faces at the start
  double smoothing = 0.5;        // share of the neighbours' average in a risky tet's extra rotation
  double propagation = 0.5;      // share of the neighbours' extra rotation a safe tet takes
  // A tet holding a risky face within this angle of straight down holds a flat overhang: it turns
  // towards the overhang's nearest edge when that costs at most edge_turn_slack_deg more than its
  // minimal turn. 10 degrees takes in the mushroom's cap (8 degrees); the slack must exceed the
  // 16 degrees by which turning its inner part towards the stem costs more than turning outwards.
  double flat_overhang_deg = 10.0;
  double edge_turn_slack_deg = 20.0;
};

constexpr double kFeatureWeight = 50.0;  // rigid-feature tets dominate the global step
// The coherent inversion guard's rounds of rolling vertices back before it gives up and cuts the
// whole step instead (on the test shapes it needs at most 9).
constexpr int kMaxRollBackRounds = 64;

void validate(const Surface& input, const SlimmingOptions& o) {
  if (input.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: Support Slimming needs a triangle mesh");
  check_surface(input);
  if (o.max_iterations < 0) throw std::invalid_argument("the iteration limit must be 0 or more");
  if (o.resolution < 1) throw std::invalid_argument("the voxel resolution must be at least 1 cell");
  if (o.max_k < 1) throw std::invalid_argument("the largest number of K-means proxies must be at least 1");
  if (!(o.margin_deg >= 0.0 && o.margin_deg < 45.0)) throw std::invalid_argument("the angular margin must be in [0, 45) degrees");
  if (!(o.max_step_deg > 0.0 && o.max_step_deg <= 180.0)) throw std::invalid_argument("the rotation step cap must be in (0, 180] degrees");
  if (!std::isfinite(o.max_deviation_pct)) throw std::invalid_argument("the deviation budget must be a finite percentage");
  if (!o.rigid_features.empty() && o.rigid_features.size() != static_cast<size_t>(input.F.rows()))
    throw std::invalid_argument("the rigid-feature marks must have one entry per face");
}

// Face-adjacent tets (sharing a triangle) of the tets marked in `from`, and those tets as
// neighbours of theirs, as lists in ascending order: the coherent step only ever pairs a tet that
// holds surface faces with its neighbours. Two tets share a face when they share three vertices;
// the candidates are the tets around one of them (CSR incidence).
std::vector<std::vector<int>> tet_neighbours(const Tets& T, Eigen::Index vertex_count, const std::vector<bool>& from) {
  std::vector<int> start(static_cast<size_t>(vertex_count) + 1, 0);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k) ++start[static_cast<size_t>(T(t, k)) + 1];
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<int> around(static_cast<size_t>(start.back())), fill(start.begin(), start.end() - 1);
  for (int t = 0; t < static_cast<int>(T.rows()); ++t)
    for (int k = 0; k < 4; ++k) around[static_cast<size_t>(fill[static_cast<size_t>(T(t, k))]++)] = t;
  std::vector<std::vector<int>> adj(static_cast<size_t>(T.rows()));
  for (int t = 0; t < static_cast<int>(T.rows()); ++t) {
    if (!from[static_cast<size_t>(t)]) continue;
    const int v0 = T(t, 0);
    for (int i = start[static_cast<size_t>(v0)]; i < start[static_cast<size_t>(v0) + 1]; ++i) {
      const int u = around[static_cast<size_t>(i)];
      if (u == t) continue;
      int shared = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) shared += T(t, a) == T(u, b);
      if (shared == 3) adj[static_cast<size_t>(t)].push_back(u);
    }
    // A neighbour across the face opposite v0 does not contain v0: look around v1 for it.
    const int v1 = T(t, 1);
    for (int i = start[static_cast<size_t>(v1)]; i < start[static_cast<size_t>(v1) + 1]; ++i) {
      const int u = around[static_cast<size_t>(i)];
      if (u == t || (T.row(u).array() == v0).any()) continue;
      int shared = 0;
      for (int a = 1; a < 4; ++a)
        for (int b = 0; b < 4; ++b) shared += T(t, a) == T(u, b);
      if (shared == 3) adj[static_cast<size_t>(t)].push_back(u);
    }
  }
  for (int t = 0; t < static_cast<int>(T.rows()); ++t)  // mirror: unmarked tets learn their marked neighbours
    if (from[static_cast<size_t>(t)])
      for (int u : adj[static_cast<size_t>(t)])
        if (!from[static_cast<size_t>(u)]) adj[static_cast<size_t>(u)].push_back(t);
  for (auto& a : adj) std::sort(a.begin(), a.end());
  return adj;
}

// Connected components of the marked faces over shared vertices; -1 for unmarked faces.
std::vector<int> feature_components(const Surface& s, const std::vector<bool>& marked, int& count) {
  std::vector<int> parent(static_cast<size_t>(s.V.rows()));
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int x) {
    while (parent[static_cast<size_t>(x)] != x) x = parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
    return x;
  };
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (marked[static_cast<size_t>(f)])
      for (int k = 1; k < 3; ++k) parent[static_cast<size_t>(find(s.F(f, k)))] = find(s.F(f, 0));
  std::vector<int> label(static_cast<size_t>(s.V.rows()), -1), face_feature(static_cast<size_t>(s.F.rows()), -1);
  count = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    if (!marked[static_cast<size_t>(f)]) continue;
    int& l = label[static_cast<size_t>(find(s.F(f, 0)))];
    if (l < 0) l = count++;
    face_feature[static_cast<size_t>(f)] = l;
  }
  return face_feature;
}

// Quaternion average (sign-aligned, weighted) of rotations; deterministic.
Eigen::Matrix3d average_rotation(const std::vector<std::pair<double, Eigen::Quaterniond>>& items) {
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  const Eigen::Vector4d ref = items.front().second.coeffs();
  for (const auto& [w, q] : items) {
    const Eigen::Vector4d c = q.coeffs();
    sum += (c.dot(ref) < 0 ? -w : w) * c;
  }
  if (sum.norm() < 1e-300) return Eigen::Matrix3d::Identity();
  Eigen::Quaterniond q;
  q.coeffs() = sum.normalized();
  return q.toRotationMatrix();
}

// Peak memory of the optimizer for a domain of `tets` tets and `vertices` vertices, in bytes.
// Measured (peak RSS of one iteration on solid cubes, 260k to 2M tets, CHOLMOD): about 650 bytes
// per tet (rest inverses, L, M and the extra rotations, face pieces, ARAP's rest shapes and
// incidence) plus the Cholesky factor, whose fill on a 3D grid grows like #DV^(4/3) (about 90
// bytes each). Rounded up, so the guard errs on the side of refusing.
double optimizer_bytes(Eigen::Index tets, Eigen::Index vertices) {
  return 700.0 * static_cast<double>(tets) + 100.0 * std::pow(static_cast<double>(vertices), 4.0 / 3.0);
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g GB", bytes / 1e9);
  return text;
}

// The run itself, on a surface whose normals point out of the part.
SlimmingResult slim_oriented(const Surface& input, const SlimmingOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  ThreadScope threads(o.threads);
  const Eigen::Vector3d d = unit_print_direction(o.print_direction);
  const double tau_solve = std::sin(std::max(0.0, o.alpha_max_deg - o.margin_deg) * M_PI / 180.0);
  const double diag = (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm();
  if (!(diag > 0.0))
    throw std::invalid_argument("the mesh has zero extent (all its vertices coincide), so there is no shape to "
                                "reshape; check the file and its units");
  OverhangOptions measure;
  measure.print_direction = d;
  measure.alpha_max_deg = o.alpha_max_deg;
  measure.plate_tolerance = o.plate_tolerance >= 0.0 ? o.plate_tolerance : 1e-3 * diag;
  const bool coherent = o.method == SlimmingMethod::Coherent;
  const CoherentSettings cs;
  auto report = [&](double fraction, const std::string& message) {
    if (o.progress && !o.progress(fraction, message)) throw Cancelled();
  };

  SlimmingResult r;
  r.before = analyse_overhang(input, measure);
  r.surface = input;
  r.displacement = Eigen::VectorXd::Zero(input.V.rows());
  r.volume_before = r.volume_after = signed_volume(input);
  IterationStats s0;
  s0.risky_area = r.before.risky_area;
  s0.risky_share = r.before.risky_share();
  s0.risky_deficit = r.before.risky_deficit;
  s0.shadow_volume = r.before.shadow_volume;
  r.history.push_back(s0);
  r.after = r.before;
  auto finish = [&](const std::string& why) {
    r.stop_reason = why;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report(1.0, "done: " + why);
    return r;
  };

  // ---- the domain and the embedding -------------------------------------------------------------
  report(0.0, "building the domain");
  TetMesh domain;
  Eigen::Array<bool, Eigen::Dynamic, 1> on_plate;
  Embedding emb;
  auto& times = r.stage_seconds;
  if (o.domain == DomainKind::Voxel) {
    VoxelDomainOptions vo;
    vo.resolution = o.resolution;
    if (o.max_memory_bytes > 0.0) vo.max_bytes = std::min(vo.max_bytes, o.max_memory_bytes);
    VoxelDomain vd;
    {
      StageTimer timer(times.domain);
      vd = voxel_domain(input, d, vo);
    }
    report(0.02, "embedding the surface");
    {
      StageTimer timer(times.embedding);
      emb = embed_surface(input, vd);
    }
    domain = std::move(vd.mesh);
    on_plate = std::move(vd.on_plate);
  } else {
    // TetGen meshes only the vertices that faces use (tetgen_domain.h): a stray vertex could not
    // be embedded, so say so now rather than "outside the domain" after TetGen has run.
    std::vector<bool> used(static_cast<size_t>(input.V.rows()), false);
    for (Eigen::Index f = 0; f < input.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) used[static_cast<size_t>(input.F(f, k))] = true;
    const auto stray = std::find(used.begin(), used.end(), false);
    if (stray != used.end())
      throw std::invalid_argument("vertex " + std::to_string(stray - used.begin()) +
                                  " belongs to no face (" + std::to_string(std::count(used.begin(), used.end(), false)) +
                                  " such vertices), and the TetGen domain cannot hold it: remove the unreferenced "
                                  "vertices or use the voxel domain");
    TetgenDomain td;
    {
      StageTimer timer(times.domain);
      td = tetgen_domain(input, d);
    }
    report(0.02, "embedding the surface");
    {
      StageTimer timer(times.embedding);
      emb = embed_surface(input, td.mesh);
    }
    domain = std::move(td.mesh);
    on_plate = std::move(td.on_plate);
  }
  r.domain_vertices = static_cast<int>(domain.V.rows());
  r.domain_tets = static_cast<int>(domain.T.rows());
  if (o.max_iterations == 0) {
    // Embed and write back only: the surface rebuilt from the undeformed domain must be the input
    // to the embedding's accuracy (embedding.h). The input's own positions are then handed back:
    // a rounding-level move can tip a face lying exactly at alpha_max (a 45° chamfer) into risky.
    Points rebuilt;
    embedded_positions(emb, domain.V, rebuilt);
    const double round_trip = (rebuilt - input.V).rowwise().norm().maxCoeff();
    if (!(round_trip <= 1e-9 * diag))
      throw std::runtime_error("the embedding rebuilds the surface only to " + std::to_string(round_trip) +
                               " mm, beyond 1e-9 of the bbox diagonal (an internal error; please report it)");
    char why[160];
    std::snprintf(why, sizeof why, "iteration limit 0: embedded and written back (round trip within %.3g mm)", round_trip);
    return finish(why);
  }
  if (r.before.risky_count == 0) return finish("no risky faces: nothing to do");

  // The memory guard for the optimizer: the voxel domain's own guard (voxel_domain.h) only covers
  // the domain, and the optimizer needs several times more. Refuse before allocating it.
  const double needed = optimizer_bytes(domain.T.rows(), domain.V.rows());
  if (o.max_memory_bytes > 0.0 && needed > o.max_memory_bytes) {
    std::string msg = "the optimizer would need about " + gigabytes(needed) + " for this domain (" +
                      std::to_string(domain.T.rows()) + " tets), more than the memory budget of " +
                      gigabytes(o.max_memory_bytes) + " allows; ";
    if (o.domain == DomainKind::Voxel) {
      // Tets grow like the cube of the resolution, the factor somewhat faster.
      const int fitting = std::max(1, static_cast<int>(o.resolution * std::cbrt(o.max_memory_bytes / needed) * 0.9));
      msg += "use a voxel resolution of at most " + std::to_string(fitting);
    } else {
      msg += "use the voxel domain, or a coarser mesh";
    }
    throw std::invalid_argument(msg);
  }

  const int nt = static_cast<int>(domain.T.rows());
  const Points n0 = face_normals(input);
  std::vector<Eigen::Matrix3d> rest_inverse(static_cast<size_t>(nt));
  for (int t = 0; t < nt; ++t) rest_inverse[static_cast<size_t>(t)] = edge_matrix(domain.V, domain.T.row(t)).inverse();

  // The constraint faces of each tet: its face pieces, less plate faces and zero-area pieces.
  std::vector<std::vector<std::pair<int, double>>> pieces(static_cast<size_t>(nt));
  for (int t = 0; t < nt; ++t)
    for (int p = emb.tet_face_offsets(t); p < emb.tet_face_offsets(t + 1); ++p) {
      const int f = emb.tet_faces(p);
      if (r.before.on_plate[static_cast<size_t>(f)] || emb.tet_face_areas(p) <= 0.0 || n0.row(f).squaredNorm() == 0.0) continue;
      pieces[static_cast<size_t>(t)].emplace_back(f, emb.tet_face_areas(p));
    }

  // Tie-break direction per tet, for straight-down faces: horizontal, from the part's vertical
  // axis out to the tet. Coherent, for the tets that hold a flat overhang: towards the nearest
  // edge of the flat overhang region, and the axis of the turn that tilts the tet that way.
  const Eigen::Vector3d centre = input.V.colwise().mean().transpose();
  std::vector<Eigen::Vector3d> tie_direction(static_cast<size_t>(nt)), edge_axis(static_cast<size_t>(nt), Eigen::Vector3d::Zero());
  auto directions_timer = std::make_unique<StageTimer>(times.local);  // the local step's input
  const double nearly_down = -std::cos(cs.flat_overhang_deg * M_PI / 180.0);
  std::vector<bool> flat_overhang;
  std::unique_ptr<const OverhangBoundary> boundary;
  if (coherent) {
    flat_overhang.resize(static_cast<size_t>(input.F.rows()));
    for (Eigen::Index f = 0; f < input.F.rows(); ++f)
      flat_overhang[static_cast<size_t>(f)] = r.before.risky[static_cast<size_t>(f)] && n0.row(f).dot(d.transpose()) <= nearly_down;
    boundary = std::make_unique<const OverhangBoundary>(input, flat_overhang);
  }
  parallel_for(nt, [&](int t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += domain.V.row(domain.T(t, k)).transpose() / 4.0;
    const Eigen::Vector3d h = (c - centre) - (c - centre).dot(d) * d;
    tie_direction[static_cast<size_t>(t)] = h.norm() > 1e-9 * diag ? h.normalized() : Eigen::Vector3d::UnitX();
    if (!boundary) return;
    bool flat = false;
    for (const auto& [face, area] : pieces[static_cast<size_t>(t)])
      flat = flat || flat_overhang[static_cast<size_t>(face)];
    if (!flat) return;
    const Eigen::Vector3d toward = boundary->toward_nearest(c, d);
    if (toward.squaredNorm() == 0.0) return;
    tie_direction[static_cast<size_t>(t)] = toward;
    edge_axis[static_cast<size_t>(t)] = toward.cross(d);  // turns -d towards `toward`
  });
  directions_timer.reset();

  // Rigid features (§IV-B): the tets holding a feature's faces share one transformation.
  int feature_count = 0;
  std::vector<int> tet_feature(static_cast<size_t>(nt), -1);
  if (!o.rigid_features.empty()) {
    const std::vector<int> face_feature = feature_components(input, o.rigid_features, feature_count);
    for (int t = 0; t < nt; ++t)
      for (int p = emb.tet_face_offsets(t); p < emb.tet_face_offsets(t + 1); ++p)
        if (face_feature[static_cast<size_t>(emb.tet_faces(p))] >= 0 && tet_feature[static_cast<size_t>(t)] < 0)
          tet_feature[static_cast<size_t>(t)] = face_feature[static_cast<size_t>(emb.tet_faces(p))];
  }

  std::vector<bool> feature_vertex(static_cast<size_t>(domain.V.rows()), false);
  for (int t = 0; t < nt; ++t)
    if (tet_feature[static_cast<size_t>(t)] >= 0)
      for (int k = 0; k < 4; ++k) feature_vertex[static_cast<size_t>(domain.T(t, k))] = true;

  // ---- the global step's matrix: factored once ----------------------------------------------------
  report(0.05, "factoring the global step");
  Eigen::VectorXd weights(nt);
  for (int t = 0; t < nt; ++t) {
    weights(t) = tet_volume(domain.V, domain.T.row(t));
    if (coherent && pieces[static_cast<size_t>(t)].empty()) weights(t) *= cs.interior_weight;
    if (coherent) {
      bool risky = false;
      for (const auto& pc : pieces[static_cast<size_t>(t)]) risky = risky || r.before.risky[static_cast<size_t>(pc.first)];
      if (risky) weights(t) *= cs.risky_boost;
    }
    if (tet_feature[static_cast<size_t>(t)] >= 0) weights(t) *= kFeatureWeight;
  }
  std::vector<int> pinned;
  for (Eigen::Index v = 0; v < on_plate.size(); ++v)
    if (on_plate(v)) pinned.push_back(static_cast<int>(v));
  ArapOptions ao;
  ao.anchor_floating_components = true;  // a part that does not touch the plate stays where it is
  std::unique_ptr<ArapSolver> solver;
  {
    StageTimer timer(times.factorization);
    solver = std::make_unique<ArapSolver>(domain, weights, pinned, ao);
  }
  const ArapSolver& arap = *solver;
  r.solver_backend = arap.backend_name();
  std::vector<bool> holds_faces(static_cast<size_t>(nt));
  for (int t = 0; t < nt; ++t) holds_faces[static_cast<size_t>(t)] = !pieces[static_cast<size_t>(t)].empty();
  const std::vector<std::vector<int>> neighbours = coherent ? tet_neighbours(domain.T, domain.V.rows(), holds_faces) : std::vector<std::vector<int>>{};

  // ---- the iterations -------------------------------------------------------------------------------
  Points V = domain.V;
  Points surface_V = input.V;
  double best_shadow = r.before.shadow_volume, best_risky = r.before.risky_area;
  // L is written whole every iteration; filled here so that its pages are set up with the rest
  // of the setup rather than in the first iteration.
  std::vector<Eigen::Matrix3d> L(static_cast<size_t>(nt), Eigen::Matrix3d::Identity()), extra(static_cast<size_t>(nt));
  std::vector<double> ae_area(static_cast<size_t>(nt)), risky_weight(static_cast<size_t>(nt));
  const double max_step = o.max_step_deg * M_PI / 180.0;
  const double edge_turn_slack = cs.edge_turn_slack_deg * M_PI / 180.0;
  const double budget = o.max_deviation_pct > 0.0 ? o.max_deviation_pct / 100.0 * diag : HUGE_VAL;
  ProxyOptions po;
  po.max_k = o.max_k;
  double piece_area = 0.0;  // AE is a share of the area that takes part in the local step
  for (const auto& tet_pieces : pieces)
    for (const auto& pc : tet_pieces) piece_area += pc.second;
  const double plate = (domain.V * d).minCoeff();
  std::string why = "iteration limit reached";

  for (int it = 1; it <= o.max_iterations; ++it) {
    r.iterations_run = it;
    // Local step: M_t from the current shape (into L_t), R_t from the rest normals turned by M_t.
    // extra_t is written for risky tets only; every other tet's extra rotation is the identity.
    auto local_timer = std::make_unique<StageTimer>(times.local);
    parallel_for(nt, [&](int t) {
      const size_t ts = static_cast<size_t>(t);
      const Eigen::Matrix3d M = closest_rotation(edge_matrix(V, domain.T.row(t)) * rest_inverse[ts]);
      L[ts] = M;
      ae_area[ts] = risky_weight[ts] = 0.0;
      const auto& pc = pieces[ts];
      if (pc.empty() || tet_feature[ts] >= 0) return;
      // Most surface tets are safe: look before building the patch.
      for (const auto& [face, area] : pc)
        if ((M * n0.row(face).transpose()).dot(d) + tau_solve < 0) risky_weight[ts] += area;
      if (!(risky_weight[ts] > 0.0)) return;
      extra[ts].setIdentity();
      Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(pc.size()));
      Eigen::VectorXd areas(static_cast<Eigen::Index>(pc.size()));
      for (size_t i = 0; i < pc.size(); ++i) {
        normals.col(static_cast<Eigen::Index>(i)) = M * n0.row(pc[i].first).transpose();
        areas(static_cast<Eigen::Index>(i)) = pc[i].second;
      }
      MinRotationOptions mo;
      mo.tie_break = tie_direction[ts];
      const ProxyRotation pr = proxy_rotation(normals, areas, d, tau_solve, mo, po);
      ae_area[ts] = pr.approximation_error * areas.sum();
      const bool minimal_found = !pr.undefined && pr.solution.feasible;
      if (edge_axis[ts].squaredNorm() > 0.0) {
        const MinRotation edge = min_rotation_about_axis(normals, d, tau_solve, edge_axis[ts]);
        if (edge.feasible && (!minimal_found || edge.angle <= pr.solution.angle + edge_turn_slack)) {
          extra[ts] = Eigen::AngleAxisd(std::min(edge.angle, max_step), edge_axis[ts]).toRotationMatrix();
          return;
        }
      }
      if (!minimal_found) return;
      const double angle = std::min(pr.solution.angle, max_step);
      extra[ts] = Eigen::AngleAxisd(angle, pr.solution.axis).toRotationMatrix();
    });

    // L_t = (extra rotation) M_t. Coherent: neighbours turn together, and safe tets next to risky
    // ones follow (each tet blends its own extra rotation with its risky neighbours', read only).
    parallel_for(nt, [&](int t) {
      const size_t ts = static_cast<size_t>(t);
      const bool risky = risky_weight[ts] > 0.0;
      std::vector<std::pair<double, Eigen::Quaterniond>> items;
      if (coherent && tet_feature[ts] < 0)
        for (int u : neighbours[ts])
          if (risky_weight[static_cast<size_t>(u)] > 0.0 && tet_feature[static_cast<size_t>(u)] < 0)
            items.emplace_back(risky_weight[static_cast<size_t>(u)], Eigen::Quaterniond(extra[static_cast<size_t>(u)]));
      if (items.empty()) {
        if (risky) L[ts] = extra[ts] * L[ts];
        return;
      }
      const double share = risky ? cs.smoothing : cs.propagation;
      const Eigen::Quaterniond mean(average_rotation(items));
      const Eigen::Quaterniond own = risky ? Eigen::Quaterniond(extra[ts]) : Eigen::Quaterniond::Identity();
      L[ts] = own.slerp(share, mean).toRotationMatrix() * L[ts];
    });

    // Rigid features: one rotation from all of the feature's faces, one shared L.
    for (int f = 0; f < feature_count; ++f) {
      Eigen::Matrix3d Qsum = Eigen::Matrix3d::Zero();
      std::vector<int> tets;
      for (int t = 0; t < nt; ++t)
        if (tet_feature[static_cast<size_t>(t)] == f) {
          tets.push_back(t);
          Qsum += weights(t) * (edge_matrix(V, domain.T.row(t)) * rest_inverse[static_cast<size_t>(t)]);
        }
      const Eigen::Matrix3d Mf = closest_rotation(Qsum);
      std::vector<Eigen::Vector3d> ns;
      std::vector<double> as;
      for (int t : tets)
        for (const auto& [face, area] : pieces[static_cast<size_t>(t)]) {
          ns.push_back(Mf * n0.row(face).transpose());
          as.push_back(area);
        }
      Eigen::Matrix3d Rf = Eigen::Matrix3d::Identity();
      if (!ns.empty()) {
        Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(ns.size()));
        Eigen::VectorXd areas(static_cast<Eigen::Index>(as.size()));
        for (size_t i = 0; i < ns.size(); ++i) {
          normals.col(static_cast<Eigen::Index>(i)) = ns[i];
          areas(static_cast<Eigen::Index>(i)) = as[i];
        }
        const ProxyRotation pr = proxy_rotation(normals, areas, d, tau_solve, {}, po);
        if (!pr.undefined && pr.solution.feasible)
          Rf = Eigen::AngleAxisd(std::min(pr.solution.angle, max_step), pr.solution.axis).toRotationMatrix();
      }
      for (int t : tets) L[static_cast<size_t>(t)] = Rf * Mf;
    }

    local_timer.reset();

    // Global step, then keep everything on or above the plate.
    auto global_timer = std::make_unique<StageTimer>(times.global);
    Points Vnew = arap.solve(L, domain.V);
    global_timer.reset();
    const Points solved = Vnew;  // the global step's own minimiser, before the guards move it
    bool guarded = false;  // whether the plate, budget or inversion guards moved the solution
    StageTimer measure_timer(times.measure);
    for (Eigen::Index v = 0; v < Vnew.rows(); ++v) {
      const double below = plate - Vnew.row(v).dot(d.transpose());
      if (below > 0.0) {
        Vnew.row(v) += below * d.transpose();
        guarded = true;
      }
    }
    Points surface_new;
    embedded_positions(emb, Vnew, surface_new);
    Eigen::VectorXd disp = (surface_new - input.V).rowwise().norm();
    // The deviation budget: the part of the step that would take a domain vertex further than
    // the budget from its rest position is rolled back (its displacement is projected onto the
    // budget ball). Surface vertices are convex combinations of domain vertices, so none of them
    // can overshoot either, while the rest of the shape keeps improving.
    bool budget_stop = false;
    if (std::isfinite(budget)) {
      std::vector<Eigen::Index> over;
      bool touches_feature = false;
      for (Eigen::Index v = 0; v < Vnew.rows(); ++v)
        if ((Vnew.row(v) - domain.V.row(v)).norm() > budget) {
          over.push_back(v);
          touches_feature = touches_feature || feature_vertex[static_cast<size_t>(v)];
        }
      if (!over.empty() && !touches_feature) {
        for (Eigen::Index v : over) {
          const Eigen::RowVector3d offset = Vnew.row(v) - domain.V.row(v);
          Vnew.row(v) = domain.V.row(v) + offset * (budget / offset.norm());
        }
      } else if (!over.empty()) {
        // Clamping vertex by vertex would bend a rigid feature: cut the whole step back to the
        // largest fraction that fits instead (positions are linear in it), and stop there.
        const Points step = Vnew - V;
        double lo = 0.0, hi = 1.0;
        for (int b = 0; b < 30; ++b) {
          const double mid = 0.5 * (lo + hi);
          const Points trial = V + mid * step;
          ((trial - domain.V).rowwise().norm().maxCoeff() <= budget ? lo : hi) = mid;
        }
        Vnew = V + lo * step;
        budget_stop = true;
      }
      if (!over.empty()) {
        guarded = true;
        embedded_positions(emb, Vnew, surface_new);
        disp = (surface_new - input.V).rowwise().norm();
      }
    }
    // Inversion guard. Coherent: the vertices of the tets that would turn inside out go back to
    // where they were, and so on for the tets that this in turn inverts, until none does (all of
    // them back is the previous, valid shape); the run goes on. A rigid feature's vertex is never
    // rolled back alone: the paper's guard then applies.
    // The paper's guard: the step is cut back to the largest fraction that keeps every tet
    // positive (bisection), and the run stops there. The bisection probes only the tets that
    // invert at the full step (a tet's volume is a cubic in the fraction, so another could in
    // principle dip in between): the fraction found is checked on every tet, and should one be
    // inverted there, the bisection is redone over all of them.
    auto is_inverted = [&](const Points& P, int t) { return edge_matrix(P, domain.T.row(t)).determinant() <= 0.0; };
    auto inverted_among = [&](const Points& P, const std::vector<int>& tets) {
      int count = 0;
      const int n = static_cast<int>(tets.size());
#pragma omp parallel for schedule(static) reduction(+ : count) if (n > 4096)
      for (int i = 0; i < n; ++i) count += is_inverted(P, tets[static_cast<size_t>(i)]);
      return count;
    };
    auto inverted_tets = [&](const Points& P) {
      std::vector<char> bad(static_cast<size_t>(nt));
#pragma omp parallel for schedule(static)
      for (int t = 0; t < nt; ++t) bad[static_cast<size_t>(t)] = is_inverted(P, t);
      std::vector<int> list;
      for (int t = 0; t < nt; ++t)
        if (bad[static_cast<size_t>(t)]) list.push_back(t);
      return list;
    };
    int held_back = 0;
    auto roll_back_inverting = [&](std::vector<int> inverting) {
      Points trial = Vnew;
      std::vector<char> back(static_cast<size_t>(V.rows()), 0);
      for (int round = 0; round < kMaxRollBackRounds && !inverting.empty(); ++round) {
        for (int t : inverting)
          for (int k = 0; k < 4; ++k) {
            const int v = domain.T(t, k);
            if (feature_vertex[static_cast<size_t>(v)]) return false;
            trial.row(v) = V.row(v);
            back[static_cast<size_t>(v)] = 1;
          }
        inverting = inverted_tets(trial);
      }
      if (!inverting.empty()) return false;
      Vnew = std::move(trial);
      held_back = static_cast<int>(std::count(back.begin(), back.end(), 1));
      return true;
    };
    bool inversion_stop = false;
    if (std::vector<int> probe = inverted_tets(Vnew); !probe.empty() && coherent && roll_back_inverting(probe)) {
      guarded = true;
      embedded_positions(emb, Vnew, surface_new);
      disp = (surface_new - input.V).rowwise().norm();
    } else if (!probe.empty()) {
      const Points step = Vnew - V;
      auto largest_fraction = [&](const std::vector<int>& tets) {
        double lo = 0.0, hi = 1.0;
        for (int b = 0; b < 20; ++b) {
          const double mid = 0.5 * (lo + hi);
          (inverted_among(V + mid * step, tets) == 0 ? lo : hi) = mid;
        }
        return lo;
      };
      double lo = largest_fraction(probe);
      if (lo > 0.0 && !inverted_tets(V + lo * step).empty()) {
        std::vector<int> all(static_cast<size_t>(nt));
        for (int t = 0; t < nt; ++t) all[static_cast<size_t>(t)] = t;
        lo = largest_fraction(all);
      }
      Vnew = V + lo * step;
      guarded = true;
      embedded_positions(emb, Vnew, surface_new);
      disp = (surface_new - input.V).rowwise().norm();
      inversion_stop = true;
    }
    Surface deformed{surface_new, input.F};
    IterationStats st;
    st.iteration = it;
    const OverhangReport now = analyse_overhang(deformed, measure);
    st.risky_area = now.risky_area;
    st.risky_share = now.risky_share();
    st.risky_deficit = now.risky_deficit;
    st.shadow_volume = now.shadow_volume;
    // One pass over the tets for the energies of the start, the minimiser and the guarded result.
    const Eigen::VectorXd energies = arap.energies(guarded ? std::vector<const Points*>{&V, &solved, &Vnew}
                                                           : std::vector<const Points*>{&V, &solved},
                                                   L);
    st.energy_start = energies(0);
    st.energy_solved = energies(1);
    st.energy = guarded ? energies(2) : energies(1);
    double ae = 0.0;
    for (int t = 0; t < nt; ++t) {
      ae += ae_area[static_cast<size_t>(t)];
      if (risky_weight[static_cast<size_t>(t)] > 0.0) ++st.risky_tets;
    }
    // Zero unless the guard cut a step whose start was already inverted.
    st.inverted_tets = inversion_stop ? static_cast<int>(inverted_tets(Vnew).size()) : 0;
    st.held_back_vertices = held_back;
    st.approximation_error = piece_area > 0.0 ? ae / piece_area : 0.0;
    st.max_displacement = disp.maxCoeff();
    st.mean_displacement = disp.mean();
    r.history.push_back(st);
    const double previous_deficit = r.history[r.history.size() - 2].risky_deficit;

    V = Vnew;
    surface_V = surface_new;
    // The support the iterate needs, estimated by its shadow volume, picks the result; the risky
    // area breaks ties (an iterate with no overhang left, or one with only plate-level ones). An
    // iterate with more risky area than the input never qualifies: neither measure may get worse.
    const bool qualifies = st.risky_area <= r.before.risky_area;
    if (qualifies &&
        (st.shadow_volume < best_shadow || (st.shadow_volume == best_shadow && st.risky_area <= best_risky))) {
      best_shadow = st.shadow_volume;
      best_risky = st.risky_area;
      r.surface.V = surface_new;
      r.after = now;
      r.displacement = disp;
      r.iterations = it;
    }
    report(0.1 + 0.9 * it / o.max_iterations, "iteration " + std::to_string(it) + ": risky area " + std::to_string(st.risky_area));
    if (inversion_stop) {
      why = "a tetrahedron would have inverted (step cut back)";
      break;
    }
    if (budget_stop) {
      why = "deviation budget reached by a rigid feature";
      break;
    }
    if (previous_deficit - st.risky_deficit < o.stall_tolerance * r.before.risky_deficit) {
      why = "overhangs stopped improving";
      break;
    }
  }
  // The result is the best iterate; its statistics close the history.
  r.history.resize(static_cast<size_t>(r.iterations) + 1);
  r.volume_after = signed_volume(r.surface);
  if (r.iterations == 0 && r.iterations_run > 0)
    why += "; no iterate needed less support than the input (shadow volume), so the input is returned unchanged";
  return finish(why);
}

}  // namespace

SlimmingResult slim_supports(const Surface& input, const SlimmingOptions& o) {
  validate(input, o);
  // The overhang rule reads the outside from the normals (DESIGN.md, Normals and orientation).
  // Faces that disagree along shared edges leave no consistent outside: refuse, rather than bend
  // the part to fix overhangs that are not there. A closed mesh that is inside out is unambiguous:
  // work on it turned over, and say so in the result.
  const EdgeTopology edges = edge_topology(input);
  require_consistent_orientation(edges);
  if (!inside_out(input, edges)) return slim_oriented(input, o);
  SlimmingResult r = slim_oriented(flipped(input), o);
  r.surface.F = input.F;  // the topology never changes, orientation included
  r.inside_out = true;
  return r;
}

}  // namespace slim
