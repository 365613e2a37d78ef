#include "core/optimizer/slimming.h"

#include <chrono>
#include <optional>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/domain/embedded_domain.h"
#include "core/geometry/checked_surface.h"
#include "core/geometry/shape_metrics.h"
#include "core/optimizer/resolution_ladder.h"
#include "core/optimizer/result_choice.h"
#include "core/optimizer/support_slimmer.h"
#include "core/platform/parallel_for.h"
#include "core/support_model/support_model.h"

// Choices the paper leaves open (the rest are documented where they live: local_step.h for the
// constraint faces, the margin and the step cap; coherence.h for the tie-break of straight-down
// faces; step_guards.h for the budget and the inversion guards; result_choice.h for the output):
//  * Stopping: the first of max_iterations; the overhang deficit (overhang.h) no longer falling by
//    stall_tolerance of its initial value; a guard that had to cut a whole step back; cancel.
//  * The result is the best iterate, not the last one (result_choice.h).

namespace slim {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The result as the input, with its overhangs; the iterations overwrite what they improve.
SlimmingResult unchanged(const Surface& input, const OverhangReport& before) {
  SlimmingResult r;
  r.before = r.after = before;
  r.surface = input;
  r.displacement = Eigen::VectorXd::Zero(input.V.rows());
  IterationStats s0;
  s0.risky_area = before.risky_area;
  s0.risky_share = before.risky_share();
  s0.risky_deficit = before.risky_deficit;
  s0.shadow_volume = before.shadow_volume;
  r.history.push_back(s0);
  return r;
}

// Iteration limit 0, embed and write back only: the surface rebuilt from the undeformed domain
// must be the input to the embedding's accuracy (embedding.h). The input's own positions are then
// handed back: a rounding-level move can tip a face lying exactly at alpha_max (a 45° chamfer)
// into risky.
std::string embed_and_write_back(const Surface& input, const EmbeddedDomain& domain, double diag) {
  Points rebuilt;
  embedded_positions(domain.embedding, domain.mesh.V, rebuilt);
  const double round_trip = (rebuilt - input.V).rowwise().norm().maxCoeff();
  if (!(round_trip <= 1e-9 * diag))
    throw std::runtime_error("the embedding rebuilds the surface only to " + std::to_string(round_trip) +
                             " mm, beyond 1e-9 of the bbox diagonal (an internal error; please report it)");
  char why[160];
  std::snprintf(why, sizeof why, "iteration limit 0: embedded and written back (round trip within %.3g mm)", round_trip);
  return why;
}

// The support model's estimate for positions of the input's mesh (mm³): the mean over grid phases
// and the slicer's own phase; none when the model refuses the surface (a part with no height, say).
struct ModelledSupport {
  double mean = 0.0, slicer_phase = 0.0;
};
std::optional<ModelledSupport> modelled_support(SupportModel& model, const Points& V, const SlimmingOptions& o) {
  SupportModelOptions m;
  m.print = o.print;
  m.threads = o.threads;
  try {
    const SupportEstimate e = model.estimate(V, m);
    return ModelledSupport{e.volume_mm3, e.phase_mm3.front()};  // phase 0: the cells as the slicer lays them
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// What the choice of iterate did, for the stop reason: the iterates the crease limit turned away,
// and why the input comes back when no iterate was chosen; "" when there is nothing to say.
std::string choice_note(const IterateChoice& choice, const ResultChoiceOptions& c, const SlimmingResult& r) {
  char note[400] = "";
  if (choice.passed_over() > 0)
    std::snprintf(note, sizeof note, "; %d iterate%s that needed less support creased more than the limit (%.3g%% of the edge length)",
                  choice.passed_over(), choice.passed_over() == 1 ? "" : "s", c.max_crease_share_pct.value_or(0.0));
  std::string why = note;
  if (choice.displaced_over() > 0) {
    std::snprintf(note, sizeof note, "; %d iterate%s that needed less support moved the surface more than the limit (%.3g%% of the bbox diagonal on average)",
                  choice.displaced_over(), choice.displaced_over() == 1 ? "" : "s", c.max_mean_displacement_pct.value_or(0.0));
    why += note;
  }
  if (r.iterations > 0) return why;
  const bool by_model = r.judged_by == ResultJudge::SupportModel;
  // Iterates the crease limit turned away did need less support: what follows is of the others.
  const std::string iterates = choice.passed_over() > 0 ? "iterates within the crease limit" : "iterates";
  if (by_model && choice.best_unsaved_pct() > 0.0) {
    std::snprintf(note, sizeof note, "; the %s needed at most %.3g%% less support than the input (support model, over the grid phases and at "
                  "the slicer's own), under the "
                  "%.3g%% worth a change of shape, so the input is returned unchanged",
                  iterates.c_str(), choice.best_unsaved_pct(), c.min_support_saving_pct);
    return why + note;
  }
  return why + "; none of the " + iterates + " needed less support than the input (" + (by_model ? "support model" : "shadow volume") +
         "), so the input is returned unchanged";
}

// The iterations under the stopping rule; the best iterate goes into r. `model` is the support
// model when it judges (r.judged_by), else null. The crease meter is the run's: after the
// iterations it measures the result too (slim_at_resolution).
std::string iterate(SupportSlimmer& slimmer, const CreaseMeter& creases, SupportModel* model, const SlimmingOptions& o,
                    double diagonal_mm, const std::function<void(double, const std::string&)>& report, SlimmingResult& r) {
  const ResultChoiceOptions& c = o.result;
  std::optional<double> max_displacement_mm;
  if (c.max_mean_displacement_pct) max_displacement_mm = *c.max_mean_displacement_pct / 100.0 * diagonal_mm;
  IterateChoice choice(r.history.front(), r.judged_by, c.max_crease_share_pct, c.min_support_saving_pct, max_displacement_mm);
  const int max_iterations = o.steps.max_iterations;
  for (int it = 1; it <= max_iterations; ++it) {
    r.iterations_run = it;
    IterationStats st = slimmer.step();
    st.iteration = it;
    if (model) {
      const auto started = std::chrono::steady_clock::now();
      if (const auto support = modelled_support(*model, slimmer.surface_positions(), o)) {
        st.support_estimate = support->mean;
        st.support_slicer_phase = support->slicer_phase;
      }
      r.stage_seconds.support_model += seconds_since(started);
    }
    // An iterate that needs more support than the least so far (or than the input's less the
    // least saving) is never chosen: its creases are not measured.
    if (c.max_crease_share_pct && choice.reads_creases(st)) {
      const auto crease_started = std::chrono::steady_clock::now();
      st.crease_share_pct = creases.share_pct(slimmer.surface_positions());
      r.stage_seconds.creases += seconds_since(crease_started);
    }
    r.history.push_back(st);
    const double previous_deficit = r.history[r.history.size() - 2].risky_deficit;
    if (choice.offer(st)) {
      r.surface.V = slimmer.surface_positions();
      r.after = slimmer.overhang();
      r.displacement = slimmer.displacement();
      r.support_after_mm3 = st.support_estimate;
      r.support_slicer_phase_after_mm3 = st.support_slicer_phase;
      r.iterations = it;
    }
    report(0.1 + 0.9 * it / max_iterations, "iteration " + std::to_string(it) + ": risky area " + std::to_string(st.risky_area));
    if (!slimmer.guard_stop().empty()) return slimmer.guard_stop() + choice_note(choice, c, r);
    if (previous_deficit - st.risky_deficit < o.steps.stall_tolerance * r.before.risky_deficit)
      return "overhangs stopped improving" + choice_note(choice, c, r);
  }
  return "iteration limit reached" + choice_note(choice, c, r);
}

// What every rung measures alike, made once per run: the input's overhangs, the support model
// (the topology of every iterate is the input's, so its adjacency is found once) and its estimate
// of the input, and the crease meter (it reads every edge of the input, a cost worth paying once).
// The support model judges when the options ask for it and it measures the input's support as
// more than 0 (a part with no height, or one that needs no support, is judged by the shadow
// volume).
struct InputMeasures {
  InputMeasures(const CheckedSurface& checked, const SlimmingOptions& o) : rule(slimming_rule(checked.get(), o)) {
    const Surface& input = checked.get();
    before = analyse_overhang(checked, rule.print);
    if (o.result.judge == ResultJudge::SupportModel) {
      model.emplace(input.F, input.V.rows());
      given = modelled_support(*model, input.V, o);
      if (!(given && given->mean > 0.0)) model.reset(), given.reset();
    }
    const auto meter_started = std::chrono::steady_clock::now();
    creases.emplace(input);
    creases_seconds = seconds_since(meter_started);
  }
  // The support model when it judges the run, else null.
  SupportModel* judging_model() { return model ? &*model : nullptr; }
  ResultJudge judge() const { return model ? ResultJudge::SupportModel : ResultJudge::ShadowVolume; }

  SlimmingRule rule;
  OverhangReport before;
  std::optional<SupportModel> model;
  std::optional<ModelledSupport> given;  // the input's, when the model judges
  std::optional<CreaseMeter> creases;
  double creases_seconds = 0.0;
};

// The run itself at one resolution, on a surface whose normals point out of the part.
SlimmingResult slim_at_resolution(const CheckedSurface& checked, const SlimmingOptions& o, InputMeasures& in) {
  const auto start = std::chrono::steady_clock::now();
  ThreadScope threads(o.threads);
  const Surface& input = checked.get();
  auto report = [&](double fraction, const std::string& message) {
    if (o.progress && !o.progress(fraction, message)) throw Cancelled();
  };
  SlimmingResult r = unchanged(input, in.before);
  r.judged_by = in.judge();
  r.print_direction = in.rule.print.d;
  if (in.given) {
    r.support_before_mm3 = r.support_after_mm3 = r.history[0].support_estimate = in.given->mean;
    r.support_slicer_phase_before_mm3 = r.support_slicer_phase_after_mm3 = r.history[0].support_slicer_phase =
        in.given->slicer_phase;
  }
  r.deviation_budget_mm = in.rule.budget_mm;
  // One crease meter for the run: the iterates' crease share, then the result's shape change on
  // every way out.
  const CreaseMeter& creases = *in.creases;
  auto finish = [&](const std::string& why) {
    r.stop_reason = why;
    const auto measured = std::chrono::steady_clock::now();
    creases.measure(r.surface.V, r.shape);
    r.stage_seconds.creases += seconds_since(measured);
    r.seconds = seconds_since(start);
    report(1.0, "done: " + why);
    return r;
  };

  report(0.0, "building the domain");
  EmbeddedDomain domain = embedded_domain(checked, in.rule.print.d, o.domain, o.resolution, o.guards.max_memory_bytes, report);
  r.stage_seconds.domain = domain.domain_seconds;
  r.stage_seconds.embedding = domain.embedding_seconds;
  r.domain_vertices = static_cast<int>(domain.mesh.V.rows());
  r.domain_tets = static_cast<int>(domain.mesh.T.rows());
  if (o.steps.max_iterations == 0) return finish(embed_and_write_back(input, domain, in.rule.diagonal_mm));
  if (r.before.risky_count == 0) return finish("no risky faces: nothing to do");

  std::string why;
  {  // The slimmer (its domain and factor are most of the run's memory) is gone before the result
     // is measured.
    SupportSlimmer slimmer(checked, std::move(domain), r.before, o, in.rule, report);
    r.solver_backend = slimmer.backend_name();
    why = iterate(slimmer, creases, in.judging_model(), o, in.rule.diagonal_mm, report, r);
    const SlimmingStageSeconds& times = slimmer.stage_seconds();
    r.stage_seconds.factorization = times.factorization;
    r.stage_seconds.local = times.local;
    r.stage_seconds.global = times.global;
    r.stage_seconds.measure = times.measure;
  }
  // The result is the best iterate; its statistics close the history.
  r.history.resize(static_cast<size_t>(r.iterations) + 1);
  return finish(why);
}

// slim_at_resolution at every rung of the resolution ladder; the run the support model prefers.
SlimmingResult slim_on_ladder(const CheckedSurface& checked, const SlimmingOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  InputMeasures in = [&] {
    ThreadScope threads(o.threads);
    return InputMeasures(checked, o);
  }();
  const std::vector<int> rungs = ladder_resolutions(o, static_cast<long>(checked.get().F.rows()));
  const double n = static_cast<double>(rungs.size());
  SlimmingResult kept;
  std::vector<ResolutionRun> runs;
  SlimmingStageSeconds total;
  total.creases = in.creases_seconds;
  for (size_t i = 0; i < rungs.size(); ++i) {
    SlimmingOptions at = o;
    at.resolution = rungs[i];
    if (o.progress && rungs.size() > 1)
      at.progress = [&o, i, n, rung = rungs[i]](double f, const std::string& message) {
        return o.progress((static_cast<double>(i) + f) / n, "resolution " + std::to_string(rung) + ": " + message);
      };
    SlimmingResult r;
    try {
      r = slim_at_resolution(checked, at, in);
    } catch (const std::exception& refused) {
      // The first rung is the user's resolution: its refusal or failure is the run's. A finer
      // rung can only be refused for its size (the input and options passed the first), or fail
      // numerically; the rungs that ran still stand, so it is left out and said so.
      if (i == 0 || dynamic_cast<const Cancelled*>(&refused)) throw;
      runs.push_back({rungs[i], std::nullopt, 0, refused.what()});
      continue;
    }
    runs.push_back({rungs[i], r.support_after_mm3, r.iterations, ""});
    const SlimmingStageSeconds& t = r.stage_seconds;
    total.domain += t.domain, total.embedding += t.embedding, total.factorization += t.factorization;
    total.local += t.local, total.global += t.global, total.measure += t.measure;
    total.support_model += t.support_model, total.creases += t.creases;
    // Nothing to slim (no risky faces) is the same at every resolution.
    const bool nothing_to_do = r.before.risky_count == 0;
    if (i == 0 || needs_less_support(r, kept)) {
      kept = std::move(r);
      kept.resolution = o.domain == DomainKind::Voxel ? rungs[i] : 0;
    }
    if (nothing_to_do) break;
  }
  kept.resolution_runs = std::move(runs);
  kept.stage_seconds = total;
  kept.seconds = seconds_since(start);
  return kept;
}

}  // namespace

EdgeTopology check_slimming_input(const Surface& input) {
  if (input.F.rows() == 0) throw std::invalid_argument("the mesh has no faces: Support Slimming needs a triangle mesh");
  check_surface(input);
  // The overhang rule reads the outside from the normals. Faces that disagree along shared edges
  // leave no consistent outside: refuse, rather than bend the part to fix overhangs that are not
  // there. A closed mesh that is inside out is unambiguous: the run works on it turned over.
  EdgeTopology edges = edge_topology(input);
  require_consistent_orientation(edges);
  if (!(bbox_diagonal(input.V) > 0.0))
    throw std::invalid_argument("the mesh has zero extent (all its vertices coincide), so there is no shape to "
                                "reshape; check the file and its units");
  return edges;
}

SlimmingResult slim_supports(const Surface& input, const SlimmingOptions& options) {
  const EdgeTopology edges = check_slimming_input(input);
  const CheckedSurface checked(input);
  validate_slimming_options(options, static_cast<long>(input.F.rows()));
  const SlimmingOptions o = method_applied(options);
  SlimmingResult r;
  if (!inside_out(input, edges)) {
    r = slim_on_ladder(checked, o);
  } else {
    r = slim_on_ladder(checked.derived(flipped(input)), o);
    r.surface.F = input.F;  // the topology never changes, orientation included
    r.inside_out = true;
  }
  r.open_edges = static_cast<long>(edges.open_edges);
  return r;
}

}  // namespace slim
