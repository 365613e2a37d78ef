// What Support Slimming (slimming.h) returns: the deformed surface, the statistics of every kept
// iteration, the support estimates and the shape's cost, and where the time went.
#pragma once

#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/shape_metrics.h"
#include "core/geometry/surface.h"
#include "core/optimizer/slimming_options.h"
#include "core/print/overhang.h"

namespace slim {

struct IterationStats {
  int iteration = 0;               // 0 is the input
  double risky_area = 0.0;         // mm²
  double risky_share = 0.0;        // of the total area
  double risky_deficit = 0.0;      // mm², see OverhangReport::risky_deficit
  double shadow_volume = 0.0;      // mm³, see OverhangReport::shadow_volume
  // mm³: the support the slicer builds, estimated by the support model (support_model.h), the
  // mean over its grid phases; none when not measured (the shadow volume judges the run, or the
  // model could not measure this iterate).
  std::optional<double> support_estimate;
  // mm³: the same estimate at the slicer's own grid phase (its first phase, SupportEstimate::
  // phase_mm3[0]); none when not measured.
  std::optional<double> support_slicer_phase;
  // % of the interior edge length creased against the input (shape_metrics.h); none when not
  // measured: the run has no crease limit, or the iterate cannot be chosen (it needed more
  // support than the least so far, which before any iterate qualifies is the input's less
  // min_support_saving_pct, result_choice.h).
  std::optional<double> crease_share_pct;
  double energy = 0.0;             // ARAP energy of the accepted positions for this iteration's L_t
  // The global step alone: ARAP energy for this iteration's L_t at the positions it started from,
  // and at its solution before the plate, budget and inversion guards touched it. The solution
  // minimises the energy, so solved <= start always.
  double energy_start = 0.0, energy_solved = 0.0;
  double approximation_error = 0.0;  // AE: area share poorly represented by its proxy (§IV-C)
  double max_displacement = 0.0;   // mm, over surface vertices
  double mean_displacement = 0.0;  // mm
  int inverted_tets = 0;
  // Coherent: domain vertices the inversion guard put back where they were in this iteration,
  // because the step would have turned a tet around them inside out.
  int held_back_vertices = 0;
  // Rigid features whose step the deviation budget cut back in this iteration: they hold at the
  // budget, in one piece, while the rest of the part goes on.
  int features_held = 0;
  int risky_tets = 0;
};

struct SlimmingStageSeconds {  // wall time per stage, summed over iterations and rungs
  double domain = 0.0;          // voxel or TetGen domain
  double embedding = 0.0;       // barycentric coordinates and clipped face pieces
  double factorization = 0.0;   // the global step's assembly and its one factorization
  double local = 0.0;           // polar decompositions, minimal rotations, coherence
  double global = 0.0;          // right-hand sides and back-substitutions
  double measure = 0.0;         // the step guards, write-back to the surface and the statistics
  double support_model = 0.0;   // the support model's estimate of every iterate (when it judges)
  double creases = 0.0;         // the crease share of the iterates that may be chosen (the crease limit)
                                // and the result's shape change (SlimmingResult::shape)
};

// One rung of the resolution ladder (resolution_ladder.h): a run at one voxel resolution.
struct ResolutionRun {
  int resolution = 0;                 // voxel cells along the longest side
  std::optional<double> support_after_mm3;  // the support model's estimate of its result (phase mean)
  int iterations = 0;                 // the iteration its result came from (0: the input)
  std::string refused;                // why it did not run or failed (a finer rung over the memory
                                      // budget, say), else empty
};

struct SlimmingResult {
  Surface surface;                    // the deformed mesh, same topology as the input
  OverhangReport before, after;       // measured at alpha_max
  // What judged the iterates: the support model when the run asked for it and it measured the
  // input's support as more than 0, else the shadow volume (result_choice.h).
  ResultJudge judged_by = ResultJudge::ShadowVolume;
  // The support model's estimate for the input and the result (mm³; none when the shadow volume
  // judged): the mean over the slicer's grid phases, which the run minimises (it must not win by
  // moving the part against the grid).
  std::optional<double> support_before_mm3, support_after_mm3;
  // The same at the slicer's own grid phase (PrusaSlicer centres its grid on the part's bounding
  // box), the part as placed (support lines along x): the model's prediction of what the slicer
  // builds for these very parts (mm³; none when not measured). It comes with the estimates above,
  // the first of the phases they average.
  std::optional<double> support_slicer_phase_before_mm3, support_slicer_phase_after_mm3;
  std::vector<IterationStats> history;  // history[0] is the input, one entry per kept iteration
  int iterations = 0;                 // the iteration the result comes from (0: the input)
  int iterations_run = 0;             // iterations computed, including any after the best one
  std::string stop_reason;
  // The input was inside out (closed, negative volume): it was computed with its faces turned
  // over, so `before`, `after` and the volumes describe the part; `surface.F` is still the input's.
  bool inside_out = false;
  long open_edges = 0;                // edges of the input used by one face: the borders of holes,
                                      // which slicers close or drop slice by slice (as the model does)
  Eigen::VectorXd displacement;       // #V, mm
  Eigen::Vector3d print_direction = Eigen::Vector3d::UnitZ();  // the run's, unit, in the result's frame
  // What the shape paid, the result against the input (shape_metrics.h's shape_change: the signed
  // enclosed volumes in mm³ and their change, the crease share, its 99th percentile), measured
  // with the run's own crease meter.
  ShapeChange shape;
  std::optional<double> deviation_budget_mm;  // the budget the run held to (none: no budget)
  int domain_vertices = 0, domain_tets = 0;  // the returned run's
  int resolution = 0;                 // the returned run's voxel resolution (0: the TetGen domain)
  std::vector<ResolutionRun> resolution_runs;  // every rung slimmed at, in order (one without a ladder)
  std::string solver_backend;
  double seconds = 0.0;               // wall time of the whole run, every rung
  using StageSeconds = SlimmingStageSeconds;
  StageSeconds stage_seconds;
};

struct Cancelled : std::exception {
  const char* what() const noexcept override { return "cancelled by the user"; }
};

}  // namespace slim
