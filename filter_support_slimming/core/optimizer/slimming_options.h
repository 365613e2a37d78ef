// Support Slimming's options (slimming.h): what the user sets, with the defaults documented beside
// each field, and the parts of the coherent method.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/domain/domain_options.h"

namespace slim {

enum class SlimmingMethod {
  Paper,    // the paper as written: per-tet minimal rotations, volume weights
  Coherent  // the default: the paper with the parts of CoherenceOptions below
};

// What the coherent method adds to the paper, part by part; each was measured on the bunny, the
// T, the mushroom and the arch with bench/slimming_curve (docs/algorithm.md has the tables). Every
// part has a value that turns it off; SlimmingMethod::Paper turns them all off (none()), whatever
// is set here.
struct CoherenceOptions {
  // The global step's weights. They are fixed before its one factorization, so they read the
  // input's risky faces.
  double interior_weight = 0.1;  // factor on tets that hold no surface face: the surface leads and
                                 // the interior follows instead of holding it back; 1 = off
  double risky_boost = 5.0;      // factor on tets that hold faces risky at the start: their
                                 // rotations are carried out instead of averaged away; 1 = off
  // The local step (coherence.h).
  double smoothing = 0.5;        // share of the face-neighbouring risky tets' mean (area-weighted
                                 // quaternion average) in a risky tet's extra rotation; 0 = off
  double propagation = 0.5;      // share of its risky neighbours' extra rotation a safe tet takes,
                                 // so a region turns as a body, not as a skin; 0 = off
  // Edge turns: a tet holding a flat overhang (a risky face within flat_overhang_deg of straight
  // down) turns about the horizontal axis that tilts it towards the nearest edge of the input's
  // flat-overhang region, when that costs at most edge_turn_slack_deg more than its minimal turn;
  // straight-down faces break their tie that way too. A flat overhang then grows a bevel or keel
  // along its edges, which a small budget can reach. 10 degrees takes in the mushroom's cap (8);
  // the slack must exceed the 16 degrees by which turning its inner part towards the stem costs
  // more than turning outwards.
  bool edge_turns = true;
  double flat_overhang_deg = 10.0;    // [0, 90)
  double edge_turn_slack_deg = 20.0;  // >= 0
  // The inversion guard (step_guards.h): true rolls the vertices of the tets a step would invert
  // back and goes on; false cuts the whole step back to the largest valid fraction and stops.
  bool local_inversion_guard = true;
  // Keep the input's enclosed volume through every global step (volume_keeping.h): what the
  // overhangs bent up would carve out of the part goes back where it is softest.
  bool keep_volume = true;
  // Each tet's extra rotation per iteration, at most (degrees), unless SlimmingOptions says
  // otherwise: small steps let the blend and the global step keep neighbours together, so the
  // surface bends smoothly instead of creasing where stiff risky tets meet the rest.
  double max_step_deg = 2.0;
  // The local step's target lies this far past alpha_max (degrees), unless SlimmingOptions says
  // otherwise. PrusaSlicer supports faces up to 1 degree past its threshold (support_model.h), and
  // the global step stops short of the local targets: aimed at that boundary (1 degree, the
  // paper's method), the faces bent up stay under it and keep their support. On the corpus at 5%
  // PrusaSlicer's support fell by 15.6% at 1 degree, 19.0% at 3, 22.9% at 10 and 22.3% at 13
  // (organic means; docs/slicer-frontier.md). [0, 45)
  double margin_deg = 10.0;
  // The result is the iterate that needs the least support by the support model (support_model.h,
  // PrusaSlicer's grid support at the print direction and alpha_max); false (and in the Paper
  // method): by the shadow volume (result_choice.h).
  bool choose_by_support_model = true;
  // The shape's smoothness as a limit: an iterate whose crease share against the input (% of the
  // interior edge length whose dihedral angle changed by more than 10 degrees, shape_metrics.h)
  // exceeds this is never returned; 0 = off. The share grows with the iterations, and where it
  // passes 2.5% the last steps bought little support (the corpus's spider: -15.2% modelled support
  // at 2.4% creases, -15.7% at 3.1%; docs/slicer-frontier.md).
  double max_crease_share_pct = 2.5;
  // The least saving worth a change of shape: when no iterate needs at least this share (%) less
  // support than the input by the support model, both over its grid phases and at the slicer's
  // own phase for the part as placed (result_choice.h), the input is returned unchanged; 0 = any
  // saving.
  // A smaller predicted saving lies within the model's error against the slicer (2.6 points on
  // average over the corpus's organic models, at its grid phase), and the slicers found none
  // there: the T, Suzanne and OpenSCAD's example017, predicted 1.7-2.5%, got -0.5% to +2.7% from
  // PrusaSlicer and up to +3.7% from Cura (docs/slicer-frontier.md). Read only when the support
  // model chooses.
  double min_support_saving_pct = 3.0;
  // Slim again at these multiples of the voxel resolution and return the result the support model
  // says needs the least support (resolution_ladder.h): 24, 32 and 48 cells by default. Read only
  // when the support model chooses, on the voxel domain, for inputs of at most
  // resolution_ladder_max_faces faces; empty = off (one run at the resolution).
  std::vector<double> resolution_ladder = {4.0 / 3.0, 2.0};  // each in (1, 4]
  long resolution_ladder_max_faces = 300000;

  static CoherenceOptions none() {
    CoherenceOptions o;
    o.interior_weight = o.risky_boost = 1.0;
    o.smoothing = o.propagation = 0.0;
    o.edge_turns = o.local_inversion_guard = o.keep_volume = o.choose_by_support_model = false;
    o.max_step_deg = 10.0;
    o.margin_deg = 1.0;
    o.max_crease_share_pct = o.min_support_saving_pct = 0.0;
    o.resolution_ladder.clear();
    return o;
  }
};

struct SlimmingOptions {
  // --- the print -------------------------------------------------------------------------------
  Eigen::Vector3d print_direction = Eigen::Vector3d::UnitZ();  // any non-zero vector
  double alpha_max_deg = 45.0;       // self-supporting angle from the vertical, [0, 90)
  double plate_tolerance = -1.0;     // mm; < 0 means 1e-3 of the bbox diagonal
  // --- the domain ------------------------------------------------------------------------------
  DomainKind domain = DomainKind::Voxel;
  int resolution = 24;               // voxel cells along the longest side of the bbox
  // --- the optimizer ---------------------------------------------------------------------------
  SlimmingMethod method = SlimmingMethod::Coherent;
  int max_iterations = 40;           // 0: embed and write back only
  double max_deviation_pct = 5.0;    // deviation budget, % of the bbox diagonal (<= 0: none)
  double max_deviation_mm = 0.0;     // > 0: the budget as this length instead (mm), e.g. a share
                                     // of the part as the user gave it before it was turned
  double stall_tolerance = 1e-3;     // stop when an iteration removes less than this share of the
                                     // initial overhang deficit
  double margin_deg = -1.0;          // solve for alpha_max - margin, measure at alpha_max;
                                     // < 0: the method's (Paper 1, Coherent its option above)
  double max_step_deg = 0.0;         // cap on each tet's extra rotation per iteration (degrees);
                                     // <= 0: the method's own (Paper 10, Coherent its option below)
  int max_k = 8;                     // K-means proxies: the largest k tried
  CoherenceOptions coherence;        // the coherent method's parts (ignored by Paper)
  // --- feature preservation (§IV-B) -------------------------------------------------------------
  // Per input face: true = part of a rigid feature. Each connected component of the marked faces
  // is one feature that moves as a single rigid body. Empty: no features.
  std::vector<bool> rigid_features;
  // --- running -----------------------------------------------------------------------------------
  int threads = 0;                   // OpenMP threads; 0: the runtime's default. Results do not
                                     // depend on it.
  // Memory budget, bytes (<= 0: none). After the domain is built, a run whose estimated peak
  // (per-tet state and the Cholesky factor) exceeds it is refused with the largest voxel
  // resolution that fits, before anything big is allocated. Before that, the voxel domain's own
  // guard (voxel_domain.h: the worst case, every cell kept, within 2 GB or this budget if less)
  // refuses absurd resolutions at once.
  double max_memory_bytes = 4e9;
  // Called with a fraction in [0, 1] and a short message before each stage (domain, embedding,
  // factorization), after every iteration and at the end. Returning false cancels: the run throws
  // slim::Cancelled at once and no result is produced. Stages in between cannot be interrupted.
  std::function<bool(double, const std::string&)> progress;
};

// The coherent parts a run uses: options.coherence for the Coherent method, none for Paper.
inline CoherenceOptions coherence_of(const SlimmingOptions& options) {
  return options.method == SlimmingMethod::Coherent ? options.coherence : CoherenceOptions::none();
}

// The step cap a run uses (degrees): options.max_step_deg when set, else the method's.
inline double max_step_of(const SlimmingOptions& options) {
  return options.max_step_deg > 0.0 ? options.max_step_deg : coherence_of(options).max_step_deg;
}

// The angular margin a run uses (degrees): options.margin_deg when set, else the method's.
inline double margin_of(const SlimmingOptions& options) {
  return options.margin_deg >= 0.0 ? options.margin_deg : coherence_of(options).margin_deg;
}

}  // namespace slim
