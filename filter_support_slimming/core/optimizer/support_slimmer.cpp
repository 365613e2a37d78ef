#include "core/optimizer/support_slimmer.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/optimizer/coherence.h"
#include "core/optimizer/costly_overhangs.h"
#include "core/optimizer/surface_guards.h"
#include "core/optimizer/rigid_proportions.h"
#include "core/optimizer/step_guards.h"
#include "core/optimizer/support_region.h"

namespace slim {

namespace {

constexpr double kFeatureWeight = 50.0;  // rigid-feature tets dominate the global step

// Adds the time of a scope to a counter.
class ScopedSeconds {
 public:
  explicit ScopedSeconds(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedSeconds() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g GB", bytes / 1e9);
  return text;
}

// The memory guard for the optimizer: the voxel domain's own guard (voxel_budget.h) only covers
// the domain, and the optimizer needs several times more. Refuse before allocating it.
void require_optimizer_memory(const TetMesh& domain, const SlimmingOptions& o) {
  const double needed = optimizer_bytes(domain.T.rows(), domain.V.rows());
  if (!(o.guards.max_memory_bytes && needed > *o.guards.max_memory_bytes)) return;
  const double budget = *o.guards.max_memory_bytes;
  std::string msg = "the optimizer would need about " + gigabytes(needed) + " for this domain (" +
                    std::to_string(domain.T.rows()) + " tets), more than the memory budget of " +
                    gigabytes(budget) + " allows; ";
  if (o.domain == DomainKind::Voxel) {
    // Tets grow like the cube of the resolution, the factor somewhat faster.
    const int fitting = std::max(1, static_cast<int>(o.resolution * std::cbrt(budget / needed) * 0.9));
    msg += "use a voxel resolution of at most " + std::to_string(fitting);
  } else {
    msg += "use the voxel domain, or a coarser mesh";
  }
  throw std::invalid_argument(msg);
}

}  // namespace

SlimmingRule slimming_rule(const Surface& input, const SlimmingOptions& o) {
  SlimmingRule rule;
  rule.diagonal_mm = bbox_diagonal(input.V);  // > 0: check_slimming_input (slimming.h) refused a point
  rule.print = print_rule(o.print, rule.diagonal_mm);
  rule.budget_mm = o.budget.mm(rule.diagonal_mm);
  return rule;
}

double optimizer_bytes(Eigen::Index tets, Eigen::Index vertices) {
  return 700.0 * static_cast<double>(tets) + 100.0 * std::pow(static_cast<double>(vertices), 4.0 / 3.0);
}

SupportSlimmer::SupportSlimmer(const CheckedSurface& input, EmbeddedDomain domain, const OverhangReport& before,
                               const SlimmingOptions& o, const SlimmingRule& rule,
                               const std::function<void(double, const std::string&)>& report)
    : input_(input.get()),
      options_(o),
      domain_(std::move(domain)),
      measure_(rule.print),
      budget_(rule.budget_mm),
      current_(input_),
      current_view_(input.derived(current_)),
      overhang_(before),
      displacement_(Eigen::VectorXd::Zero(input_.V.rows())) {
  const TetMesh& mesh = domain_.mesh;
  require_optimizer_memory(mesh, o);
  const Eigen::Vector3d& d = rule.print.d;

  const Points n0 = face_normals(input_);
  local_.set_rest(mesh);
  const std::vector<bool> costly = costly_overhangs(input_, before, d, o.coherence.costly_share);
  std::vector<bool> left_alone = before.on_plate;  // no piece: no turn asked for
  for (size_t f = 0; f < left_alone.size(); ++f) left_alone[f] = left_alone[f] || (before.risky[f] && !costly[f]);
  local_.pieces = constraint_pieces(domain_.embedding, mesh.T.rows(), left_alone, n0);
  local_.d = d;
  local_.tau = std::sin(std::max(0.0, rule.print.alpha_max_deg - *o.steps.margin_deg) * M_PI / 180.0);
  local_.max_step = *o.steps.max_step_deg * M_PI / 180.0;
  local_.edge_slack = o.coherence.edge_turn_slack_deg * M_PI / 180.0;
  local_.proxies.max_k = o.steps.max_k;
  {
    ScopedSeconds timer(times_.local);  // the local step's input
    TieDirections ties = tie_directions(input_, mesh, local_.pieces, n0, costly, d, rule.diagonal_mm, o.coherence);
    local_.tie = std::move(ties.tie);
    local_.edge_axis = std::move(ties.edge_axis);
  }
  local_.rest_normals = n0;
  features_ = std::make_unique<RigidFeatures>(input_, o.rigid_features, domain_.embedding, mesh);
  local_.skip = features_->tet_flags();

  report(0.05, "factoring the global step");
  factor_global_step(costly, rule.diagonal_mm);
  state_ = local_.make_state();
  V_ = mesh.V;
  for (const auto& tet_pieces : local_.pieces)
    for (const auto& pc : tet_pieces) piece_area_ += pc.second;  // AE is a share of this area
  plate_ = (mesh.V * d).minCoeff();
  volume_target_ = signed_volume(input_);
  if (o.keep_volume) volume_ = std::make_unique<VolumeKeeping>(domain_.embedding, input_.F, mesh.V.rows());
  if (o.guards.surface_guard)
    surface_guards_ = std::make_unique<SurfaceGuards>(input_, domain_.embedding, d, o.guards.max_rise_pct);
}

// Weights: the rest volumes (the paper), with the coherent factors and the features' weight;
// the plate vertices held; a part that does not touch the plate stays where it is. costly: #F, the
// overhangs turned (costly_overhangs.h), which the boost and the free region read.
void SupportSlimmer::factor_global_step(const std::vector<bool>& costly, double diagonal_mm) {
  const TetMesh& mesh = domain_.mesh;
  const int nt = static_cast<int>(mesh.T.rows());
  weights_.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& pieces = local_.pieces[static_cast<size_t>(t)];
    weights_(t) = tet_volume(mesh.V, mesh.T.row(t));
    if (pieces.empty()) weights_(t) *= options_.coherence.interior_weight;
    const bool risky = std::any_of(pieces.begin(), pieces.end(), [&](const auto& pc) { return costly[static_cast<size_t>(pc.first)]; });
    if (risky) weights_(t) *= options_.coherence.risky_boost;
    if (features_->tet_feature()[static_cast<size_t>(t)] >= 0) weights_(t) *= kFeatureWeight;
  }
  std::vector<int> pinned;
  for (Eigen::Index v = 0; v < domain_.on_plate.size(); ++v)
    if (domain_.on_plate(v)) pinned.push_back(static_cast<int>(v));
  ArapOptions ao;
  ao.anchor_floating_components = true;
  {
    ScopedSeconds timer(times_.factorization);
    const Eigen::VectorXd anchors = region_anchors(input_, costly, mesh, diagonal_mm, options_.region);
    arap_ = std::make_unique<ArapSolver>(mesh, weights_, pinned, anchors, ao);
    if (options_.hold_proportions) {
      const std::vector<Points> C = stretch_constraints(input_, domain_.embedding, mesh.V.rows());
      arap_->set_constraints(C, constraint_values(C, mesh.V));
    }
  }
  if (options_.coherence.smoothing > 0.0 || options_.coherence.propagation > 0.0) {
    std::vector<bool> holds_faces(static_cast<size_t>(nt));
    for (int t = 0; t < nt; ++t) holds_faces[static_cast<size_t>(t)] = !local_.pieces[static_cast<size_t>(t)].empty();
    neighbours_ = tet_neighbours(mesh.T, mesh.V.rows(), holds_faces);
  }
}

IterationStats SupportSlimmer::step() {
  guard_stop_.clear();
  {
    ScopedSeconds timer(times_.local);
    local_.run(V_, state_);
    blend_rotations(neighbours_, local_.skip, options_.coherence.smoothing, options_.coherence.propagation, state_);
    features_->fit(V_, weights_, local_, state_);
  }
  Points proposed;
  {
    ScopedSeconds timer(times_.global);
    if (volume_) {
      Points response;
      proposed = arap_->solve_with_response(state_.L, domain_.mesh.V, volume_->load(V_), response);
      volume_->keep(volume_target_, response, proposed);
    } else {
      proposed = arap_->solve(state_.L, domain_.mesh.V);
    }
  }
  ScopedSeconds timer(times_.measure);
  const Points solved = proposed;  // the global step's own minimiser, before the guards move it
  int held_back = 0, features_held = 0;
  bool inversion_cut = false;
  const bool guarded = guard(proposed, held_back, features_held, inversion_cut);
  IterationStats stats = measure(solved, proposed, guarded, inversion_cut, held_back);
  stats.features_held = features_held;
  V_ = std::move(proposed);
  return stats;
}

// After the plate and the budget: the vertices of the tets a step would invert, and with the
// surface guards (surface_guards.h) those under folded faces or above the top's allowance, go
// back, in rounds (step_guards.h). Should the rounds run out, or for the paper's method, the step
// is cut back to the largest fraction that inverts nothing, and a surface still at fault takes
// the whole step back (the current iterate has no fault).
bool SupportSlimmer::guard(Points& proposed, int& held_back, int& features_held, bool& inversion_cut) {
  const Tets& T = domain_.mesh.T;
  bool guarded = keep_above_plate(proposed, measure_.d, plate_);
  if (budget_) {
    const BudgetGuard budget = keep_within_budget(domain_.mesh.V, V_, proposed, *budget_, features_->vertex_feature());
    guarded = guarded || budget.moved();
    features_held = budget.groups_held;
  }
  auto surface_faults = [&](const Points& P) { return surface_guards_ ? surface_guards_->faulty_tets(P) : std::vector<int>(); };
  auto faulty = [&](const Points& P) {
    const std::vector<int> a = inverted_tets(P, T), b = surface_faults(P);
    std::vector<int> both;
    std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
    return both;
  };
  std::vector<int> now = faulty(proposed);
  if (now.empty()) return guarded;
  if (options_.guards.local_inversion_guard &&
      roll_back_until(V_, proposed, T, features_->vertex_feature(), std::move(now), faulty, held_back))
    return true;
  const std::vector<int> probe = inverted_tets(proposed, T);
  if (!probe.empty()) {
    cut_back_to_valid(V_, proposed, T, probe);
    inversion_cut = true;
    guard_stop_ = "a tetrahedron would have inverted (step cut back)";
  }
  if (!surface_faults(proposed).empty()) {
    proposed = V_;
    held_back = static_cast<int>(V_.rows());
  }
  return true;
}

IterationStats SupportSlimmer::measure(const Points& solved, const Points& accepted, bool guarded, bool inversion_cut,
                                       int held_back) {
  embedded_positions(domain_.embedding, accepted, current_.V);
  displacement_ = (current_.V - input_.V).rowwise().norm();
  overhang_ = analyse_overhang(current_view_, measure_);
  IterationStats st;
  st.risky_area = overhang_.risky_area;
  st.risky_share = overhang_.risky_share();
  st.risky_deficit = overhang_.risky_deficit;
  st.shadow_volume = overhang_.shadow_volume;
  // One pass over the tets for the energies of the start, the minimiser and the guarded result.
  const Eigen::VectorXd energies = arap_->energies(
      guarded ? std::vector<const Points*>{&V_, &solved, &accepted} : std::vector<const Points*>{&V_, &solved}, state_.L);
  st.energy_start = energies(0);
  st.energy_solved = energies(1);
  st.energy = guarded ? energies(2) : energies(1);
  double ae = 0.0;
  for (size_t t = 0; t < state_.ae_area.size(); ++t) {
    ae += state_.ae_area[t];
    if (state_.risky_area[t] > 0.0) ++st.risky_tets;
  }
  // Zero unless the guard cut a step whose start was already inverted.
  st.inverted_tets = inversion_cut ? static_cast<int>(inverted_tets(accepted, domain_.mesh.T).size()) : 0;
  st.held_back_vertices = held_back;
  st.approximation_error = piece_area_ > 0.0 ? ae / piece_area_ : 0.0;
  st.max_displacement = displacement_.maxCoeff();
  st.mean_displacement = displacement_.mean();
  return st;
}

}  // namespace slim
