// Support Slimming's options (slimming.h), grouped by what they govern: the print, the domain, the
// deviation budget, the steps, the coherent method's parts, the choice of result, the resolution
// ladder, the volume, the guards. Each field's default is beside it; a setting that can be "the
// method's own" or "none" is a std::optional or an explicit type, never a magic number.
// method_applied() resolves the method once; the optimizer reads only what it returns.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/domain/domain_options.h"
#include "core/print/print_setup.h"

namespace slim {

enum class SlimmingMethod {
  Paper,    // the paper as written: per-tet minimal rotations, volume weights
  Coherent  // the default: the paper with the coherent parts below
};

// How far any surface vertex may move from where it was (a constraint, not a stop: every step is
// cut back to it, step_guards.h).
class DeviationBudget {
 public:
  static DeviationBudget none() { return DeviationBudget(Kind::None, 0.0); }
  // A share of the part's bounding-box diagonal, in percent (> 0).
  static DeviationBudget share_of_diagonal(double percent) { return DeviationBudget(Kind::Share, percent); }
  // A length in mm (> 0): e.g. a share of the part as the user gave it before it was turned.
  static DeviationBudget length(double mm) { return DeviationBudget(Kind::Length, mm); }
  // The dialog's and the CLI's convention: a percentage, 0 or less for none (NaN stays a share, for
  // validate() to refuse).
  static DeviationBudget from_percent(double percent) { return percent <= 0.0 ? none() : share_of_diagonal(percent); }
  // The budget in mm for a part whose bounding-box diagonal is diagonal_mm; nullopt: none.
  std::optional<double> mm(double diagonal_mm) const {
    if (kind_ == Kind::None) return std::nullopt;
    return kind_ == Kind::Length ? value_ : value_ / 100.0 * diagonal_mm;
  }
  bool is_share() const { return kind_ == Kind::Share; }
  // The share in percent when the budget is one, else none.
  std::optional<double> share_percent() const { return is_share() ? std::optional<double>(value_) : std::nullopt; }
  // Throws std::invalid_argument for a share or length that is not finite and positive.
  void validate() const;

 private:
  enum class Kind { None, Share, Length };
  DeviationBudget(Kind kind, double value) : kind_(kind), value_(value) {}
  Kind kind_;
  double value_;
};

// The iterations and the local step.
struct StepOptions {
  int max_iterations = 40;        // 0: embed and write back only
  double stall_tolerance = 1e-3;  // stop when an iteration removes less than this share of the
                                  // input's overhang deficit
  // The local step aims at alpha_max - margin and the overhangs are measured at alpha_max
  // (degrees, [0, 45)); none: the method's (Paper 1, Coherent 10). The slicer supports faces up to
  // about a degree past its threshold and the global step stops short of the local targets, so a
  // target at the threshold leaves the faces bent up just under it, still supported.
  std::optional<double> margin_deg;
  // Each tet's extra rotation per iteration, at most (degrees, (0, 180]); none: the method's
  // (Paper 10, Coherent 2). Small steps let the blend and the global step keep neighbours
  // together, so the surface bends instead of creasing where stiff tets meet the rest.
  std::optional<double> max_step_deg;
  int max_k = 8;                  // K-means proxies: the largest k tried
};

// What the coherent method adds to the paper's local and global steps; each part has a value that
// turns it off, and none() turns them all off (docs/algorithm.md measures each).
struct CoherenceOptions {
  // The global step's weights, fixed before its one factorization, so they read the input's risky
  // faces.
  double interior_weight = 0.1;  // factor on tets that hold no surface face: the surface leads and
                                 // the interior follows instead of holding it back; 1 = off
  double risky_boost = 5.0;      // factor on tets that hold faces risky at the start: their
                                 // rotations are carried out instead of averaged away; 1 = off
  // The overhangs turned (costly_overhangs.h): the costliest risky faces, by the support column
  // under each, that carry this share of their support cost, (0, 1]; 1 = every risky face. The
  // others get no turn, no free region and no boost. On the corpus's tune half a share below 1
  // did not pay (docs/algorithm.md), so every risky face is turned.
  double costly_share = 1.0;
  // The local step (coherence.h).
  double smoothing = 0.5;        // share of the face-neighbouring risky tets' mean (area-weighted
                                 // quaternion average) in a risky tet's extra rotation; 0 = off
  double propagation = 0.5;      // share of its risky neighbours' extra rotation a safe tet takes,
                                 // so a region turns as a body, not as a skin; 0 = off
  // Edge turns: a tet holding a flat overhang (a risky face within flat_overhang_deg of straight
  // down) turns about the horizontal axis that tilts it towards the nearest edge of the input's
  // flat-overhang region, when that costs at most edge_turn_slack_deg more than its minimal turn;
  // straight-down faces break their tie that way too. A flat overhang then grows a bevel or keel
  // along its edges, which a small budget can reach. The slack must exceed what turning the inner
  // part of a wide cap towards its stem costs over turning it outwards.
  bool edge_turns = true;
  double flat_overhang_deg = 10.0;    // [0, 90)
  double edge_turn_slack_deg = 20.0;  // [0, 180]

  static CoherenceOptions none() {
    CoherenceOptions o;
    o.interior_weight = o.risky_boost = o.costly_share = 1.0;
    o.smoothing = o.propagation = 0.0;
    o.edge_turns = false;
    return o;
  }
};

// What judges the iterates (result_choice.h).
enum class ResultJudge {
  SupportModel,  // the support model's estimate of what the slicer builds (support_model.h)
  ShadowVolume   // the volume under the overhangs (overhang.h), the cruder estimate
};

// Which iterate the run returns (result_choice.h).
struct ResultChoiceOptions {
  // The support model judges when it can measure the input's support (a part with no height, or
  // one that needs none, falls back to the shadow volume).
  ResultJudge judge = ResultJudge::SupportModel;
  // An iterate whose crease share against the input (% of the interior edge length whose dihedral
  // angle changed by more than 10 degrees, shape_metrics.h) exceeds this is never returned; none:
  // no limit. The share grows with the iterations while the last steps buy little support.
  std::optional<double> max_crease_share_pct = 2.0;  // (0, 100]
  // An iterate whose surface vertices moved further than this on average (% of the input's
  // bounding-box diagonal) is never returned; none: no limit. The shape should change where the
  // support is, not everywhere.
  std::optional<double> max_mean_displacement_pct = 1.5;  // (0, 100]
  // The least saving worth a change of shape: when no iterate needs at least this share (%) less
  // support than the input by the support model, both over its grid phases and at the slicer's own
  // phase for the part as placed, the input is returned unchanged; 0: any saving. A smaller
  // predicted saving lies within the model's error against the slicer. Read only when the support
  // model judges.
  double min_support_saving_pct = 3.0;  // [0, 100)
};

// Slim again at these multiples of the voxel resolution and return the result the support model
// says needs the least support (resolution_ladder.h): 24, 32 and 48 cells by default. Read only
// when the support model judges, on the voxel domain, for inputs of at most max_faces faces.
struct LadderOptions {
  std::vector<double> multiples = {4.0 / 3.0, 2.0};  // each in (1, 4]; empty: one run
  long max_faces = 300000;                           // >= 0
};

// Where the part may move (support_region.h): the global step anchors every domain vertex farther
// than free_radius_share of the bounding-box diagonal from the faces that need support to where
// it was, fully beyond a further ramp_share. So the underside is reshaped where the support is and
// the rest of the part keeps its place, size and proportions. stiffness 0 turns the anchors off
// (the part may then stretch: taller and thinner, which buys little support).
struct RegionOptions {
  double free_radius_share = 0.10;  // [0, 10]: share of the diagonal free of springs
  double ramp_share = 0.10;         // [0, 10]: share of the diagonal over which they grow
  double stiffness = 0.1;           // >= 0, unitless (the springs per mm^3 of domain)
  static RegionOptions none() {
    RegionOptions o;
    o.stiffness = 0.0;
    return o;
  }
};

// What protects the run and the machine.
struct GuardOptions {
  // The inversion guard (step_guards.h): true rolls the vertices of the tets a step would invert
  // back and goes on; false cuts the whole step back to the largest valid fraction and stops.
  bool local_inversion_guard = true;
  // The surface guards (surface_guards.h): true rolls back the vertices of the tets under faces a
  // step would fold over (turn past 90 degrees) or lift above the top's allowance below.
  bool surface_guard = true;
  // The surface's top may rise at most this share (%) of the part's height along the print
  // direction (surface_guards.h); none: no limit. A part that grows taller may no longer fit.
  std::optional<double> max_rise_pct = 1.0;  // [0, 100]
  // Memory budget (bytes); none: no budget. After the domain is built, a run whose estimated peak
  // (per-tet state and the Cholesky factor) exceeds it is refused with the largest voxel
  // resolution that fits, before anything big is allocated. Before that, the voxel domain's own
  // guard (voxel_domain.h: the worst case, every cell kept, within 2 GB or this budget if less)
  // refuses absurd resolutions at once.
  std::optional<double> max_memory_bytes = 4e9;
};

struct SlimmingOptions {
  PrintSetup print;                  // direction, alpha_max, plate rule
  // The domain.
  DomainKind domain = DomainKind::Voxel;
  int resolution = 24;               // voxel cells along the longest side of the bbox, >= 1
  // The optimizer.
  SlimmingMethod method = SlimmingMethod::Coherent;
  DeviationBudget budget = DeviationBudget::share_of_diagonal(5.0);
  StepOptions steps;
  CoherenceOptions coherence;        // read by the Coherent method only
  ResultChoiceOptions result;
  LadderOptions ladder;
  // Keep the input's enclosed volume through every global step (volume_keeping.h): what the
  // overhangs bent up would carve out of the part goes back where it is softest.
  bool keep_volume = true;
  RegionOptions region;              // read by the Coherent method only
  // Hold the part's proportions (rigid_proportions.h): every global step keeps the best-fit affine
  // map from the input to the result free of stretch and squash, so the part does not come back
  // taller and thinner. false lets it stretch (a stretch buys little support).
  bool hold_proportions = true;      // read by the Coherent method only
  GuardOptions guards;
  // Feature preservation (§IV-B). Per input face: true = part of a rigid feature. Each connected
  // component of the marked faces is one feature that moves as a single rigid body. Empty: none.
  std::vector<bool> rigid_features;
  // Running.
  int threads = 0;                   // OpenMP threads; 0: the runtime's default. Results do not
                                     // depend on it.
  // Called with a fraction in [0, 1] and a short message before each stage (domain, embedding,
  // factorization), after every iteration and at the end. Returning false cancels: the run throws
  // slim::Cancelled at once and no result is produced. Stages in between cannot be interrupted.
  std::function<bool(double, const std::string&)> progress;
};

// The options a run reads, the method applied: for Coherent, the margin 10 and step cap 2 where
// not set; for Paper, every coherent part off (CoherenceOptions::none()), the shadow volume as the
// judge with no crease, displacement or least-saving limit, no ladder, no volume keeping, the part
// free to stretch (allow_stretch), the whole-step inversion guard and no surface guard, and the
// margin 1 and step cap 10 where not set. Every other field as given.
SlimmingOptions method_applied(const SlimmingOptions& options);

// The part may move as a whole (the CLI's --allow-stretch, the filter's "Allow stretch"): no
// springs to what the support does not need (RegionOptions::none()), no hold on its proportions
// and no limit on its top's rise. The result limits (creases, mean displacement) stay as set.
void allow_stretch(SlimmingOptions& options);

// Throws std::invalid_argument, in words a user can act on, for a value out of its range
// (`faces`: the input's face count, for the rigid-feature marks).
void validate_slimming_options(const SlimmingOptions& options, long faces);

}  // namespace slim
