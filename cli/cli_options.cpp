#include "cli_options.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/platform/version.h"

namespace slim::cli {

namespace {

const char* kUsage = R"(usage: support-slim IN -o OUT [options]
       support-slim IN... --out-dir DIR [options]

Reshapes a mesh so that it needs less support material when 3D printed (local/global
minimal-rotation optimizer). Reads and writes PLY, STL, OBJ, OFF and 3MF. OUT has IN's vertex
list and face list in IN's order: nothing is welded, dropped or reordered (STL, which stores each
triangle's corners apart, is welded when read; a 3MF's build is read as one plate in mm and
written back with its unit, objects and placements), and IN's vertex colours, texture coordinates,
vertex quality and selection pass through; vertex normals too, recomputed where a vertex moved.
The run replaces three face attributes: face quality becomes n.d + sin(alpha_max) (negative =
still risky; PLY), face colour its ramp (PLY, OFF, STL, 3MF), and the face selection the
still-risky faces (PLY); where IN has no vertex colours, vertex colour and quality say how far
each vertex moved (PLY; colour also OFF; see --colour). OUT is in the input's frame (no
rescaling, no recentring), or with --orient in the print pose the search chose. See
docs/files-and-attributes.md.

Exit status: 0 done (also when the part comes back unchanged), 1 the run failed, 2 bad usage (a
flag, a value or an output path), 3 a bad input file (missing, unreadable, not a mesh, or a mesh
the run refuses). A batch (--out-dir) exits 0 when every file was done, 1 when any failed (its
row says why), 2 for bad usage before any work.

The mesh is taken in millimetres at the size it will print (only a 3MF says its unit): a
part under 5 mm or over 1 m across gets a warning, and --scale F scales IN first (OUT is then
scaled too).

options:
  -o, --output FILE        where to write the result (one IN; several take --out-dir)
  --scale F                scale IN by F (> 0) about the origin first: 25.4 for inches,
                           10 for centimetres, 1000 for metres                        [1]
  --angle DEG              self-supporting angle from the vertical, [0, 90)       [45]
  --dir X,Y,Z              print direction                                     [0,0,1]
  --plate-tolerance MM     faces this close to the lowest point rest on the plate
                                                                  [1e-3 of the bbox diagonal]
  --resolution N           voxel cells along the longest side                      [24]
                           (coherent: also 4/3 and 2 x N for parts up to 300,000 faces;
                           the result the support model prefers is kept)
  --one-resolution         slim at --resolution alone: no 4/3 and 2 x N (several times faster)
  --domain voxel|tetgen    the tetrahedral domain                               [voxel]
  --method coherent|paper  coherent (default) or the paper's method as written [coherent]
  --iterations N           iteration limit; 0 embeds and writes back only          [40]
  --max-deviation PCT      deviation budget, % of the bbox diagonal (0: none)       [5]
  --max-k K                largest number of K-means proxies per tet                 [8]
  --max-creases PCT        never return a result whose creases (edges whose dihedral angle
                           changed by more than 10 deg) exceed PCT % of the edge length;
                           0: no limit; the paper's method has none                  [2]
  --max-displacement PCT   never return a result whose surface moved further than PCT % of the
                           bbox diagonal on average; 0: no limit                     [1.5]
  --allow-stretch          let the whole part move: no anchoring of what lies away from the
                           overhangs and no hold on its proportions (it may come back taller
                           and thinner; off by default)
  --min-saving PCT         return the input unchanged unless the support model finds a result
                           needing at least PCT % less support, over its grid phases and at
                           the slicer's own; 0: any saving; the paper's method chooses by
                           the shadow volume and has none                              [3]
  --features FILE          rigid features: a text file of face ids (0-based)
  --features-from-mesh     rigid features: the faces selected in IN (PLY face flags)
  --orient                 first turn the part into the print pose that needs the least support
                           (estimated), then slim it there; OUT is in that pose, +Z up, resting
                           on z = 0, and the displacement counts only the deformation
  --orient-effort fast|normal|thorough
                           how many directions the orientation search tries         [normal]
  --oriented-output FILE   with --orient: also write the oriented part before slimming
  --out-dir DIR            a batch: slim each IN into DIR/<name>_slimmed.<its extension>, go on
                           past a file that fails, and print one table (file, support, shape,
                           status); exit 1 when any file failed
  --colour moved|risky|none
                           what OUT's colours say: moved colours each vertex by how far it
                           moved (blue: not at all, red: the budget; PLY and OFF, when IN has no
                           vertex colours of its own) and each face by n.d + sin(alpha_max) (red:
                           still risky); risky only the faces; none adds no colours (nor face
                           quality): IN's own pass through                          [moved]
  --report FILE.json       also write every figure of the summary as JSON (docs/usage.md); with
                           --out-dir, one JSON object per line, per file
  --threads N              OpenMP threads (the result does not depend on it)
  --quiet                  no progress on stderr
  --verbose                the run's internals in the summary too: the proxies, the domain and
                           solver, each resolution's result, the orientation's best poses
  --version                the version, and exit
  -h, --help               this text
)";

double number(const std::string& flag, const std::string& text) {
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  die(flag + " expects a number, got '" + text + "'");
}

int integer(const std::string& flag, const std::string& text) {
  const double v = number(flag, text);
  if (v != std::floor(v) || std::abs(v) > 1e9) die(flag + " expects a whole number, got '" + text + "'");
  return static_cast<int>(v);
}

// v, or the end with "FLAG expects a value BOUND, got V" when `ok` is false.
double required(bool ok, const std::string& flag, double v, const std::string& bound) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  if (!ok) die(flag + " expects a value " + bound + ", got " + text);
  return v;
}

// A number that must not be negative (a typo's minus sign must not turn a limit off).
double at_least_zero(const std::string& flag, double v, const std::string& zero_means) {
  return required(v >= 0.0, flag, v, ">= 0" + zero_means);
}

double positive(const std::string& flag, double v) { return required(v > 0.0, flag, v, "> 0"); }

// A limit as the CLI and the dialog give it (creases, displacement): a percentage, 0 for no limit.
std::optional<double> limit_pct(double pct) { return pct == 0.0 ? std::nullopt : std::optional<double>(pct); }

Eigen::Vector3d vector3(const std::string& flag, const std::string& text) {
  std::stringstream ss(text);
  std::string part;
  std::vector<double> v;
  while (std::getline(ss, part, ',')) v.push_back(number(flag, part));
  if (v.size() != 3) die(flag + " expects X,Y,Z, got '" + text + "'");
  return {v[0], v[1], v[2]};
}

// One input and -o, or any number of inputs and --out-dir; what names one file fits one input.
void check_files_asked(CliOptions& c) {
  if (c.inputs.empty()) die("no input mesh given (see --help)");
  if (!c.batch()) {
    if (c.inputs.size() > 1) die("more than one input mesh given: " + c.inputs[0] + " and " + c.inputs[1] + " (--out-dir DIR runs each)");
    if (c.out.empty()) die("no output given: use -o OUT (or --out-dir DIR)");
    c.in = c.inputs[0];
    return;
  }
  if (!c.out.empty()) die("-o names one output; --out-dir names each after its input: give one of them");
  if (!c.oriented_out.empty()) die("--oriented-output names one file; it does not go with --out-dir");
  if (!c.features_file.empty() && c.inputs.size() > 1) die("--features names the faces of one mesh; it does not go with several inputs");
}

}  // namespace

std::vector<bool> read_face_ids(const std::string& path, long long faces) {
  std::ifstream in(path);
  if (!in) die("cannot read the features file " + path);
  std::vector<bool> marked(static_cast<size_t>(faces), false);
  long long id = 0;
  while (in >> id) {
    if (id < 0 || id >= faces)
      die("the features file names face " + std::to_string(id) + ", but the mesh has " + std::to_string(faces) + " faces");
    marked[static_cast<size_t>(id)] = true;
  }
  if (!in.eof()) die("the features file " + path + " must hold whole face ids separated by white space");
  return marked;
}


[[noreturn]] void die(const std::string& reason, int code) {
  std::cerr << "support-slim: " << reason << "\n";
  std::exit(code);
}

CliOptions parse_arguments(const std::vector<std::string>& args) {
  CliOptions c;
  SlimmingOptions& o = c.slimming;
  bool dir_given = false, creases_given = false, saving_given = false, shape_given = false;
  auto value = [&](size_t& i) -> const std::string& {
    if (i + 1 >= args.size()) die(args[i] + " needs a value");
    return args[++i];
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      std::exit(0);
    } else if (a == "--version") {
      std::cout << "support-slim " << version() << "\n";
      std::exit(0);
    } else if (a == "-o" || a == "--output") c.out = value(i);
    else if (a == "--out-dir") c.out_dir = value(i);
    else if (a == "--scale") c.scale = positive(a, number(a, value(i)));
    else if (a == "--angle") o.print.alpha_max_deg = number(a, value(i));
    else if (a == "--dir") o.print.direction = vector3(a, value(i)), dir_given = true;
    else if (a == "--plate-tolerance") o.print.plate = PlateRule::within(number(a, value(i)));
    else if (a == "--resolution") o.resolution = integer(a, value(i));
    else if (a == "--one-resolution") o.ladder.multiples.clear();
    else if (a == "--domain") {
      const std::string& v = value(i);
      if (v == "voxel") o.domain = DomainKind::Voxel;
      else if (v == "tetgen") o.domain = DomainKind::TetGen;
      else die("--domain expects voxel or tetgen, got '" + v + "'");
    } else if (a == "--method") {
      const std::string& v = value(i);
      if (v == "coherent") o.method = SlimmingMethod::Coherent;
      else if (v == "paper") o.method = SlimmingMethod::Paper;
      else die("--method expects coherent or paper, got '" + v + "'");
    } else if (a == "--iterations") o.steps.max_iterations = integer(a, value(i));
    else if (a == "--max-deviation") o.budget = DeviationBudget::from_percent(at_least_zero(a, number(a, value(i)), " (0: no budget)"));
    else if (a == "--max-k") o.steps.max_k = integer(a, value(i));
    else if (a == "--max-creases") o.result.max_crease_share_pct = limit_pct(number(a, value(i))), creases_given = true;
    else if (a == "--min-saving") o.result.min_support_saving_pct = number(a, value(i)), saving_given = true;
    else if (a == "--max-displacement")
      o.result.max_mean_displacement_pct = limit_pct(number(a, value(i))), shape_given = true;
    else if (a == "--allow-stretch") allow_stretch(o), shape_given = true;
    else if (a == "--features") c.features_file = value(i);
    else if (a == "--features-from-mesh") c.features_from_mesh = true;
    else if (a == "--orient") c.orient = true;
    else if (a == "--orient-effort") {
      const std::string& v = value(i);
      if (v == "fast") c.effort = OrientationEffort::Fast;
      else if (v == "normal") c.effort = OrientationEffort::Normal;
      else if (v == "thorough") c.effort = OrientationEffort::Thorough;
      else die("--orient-effort expects fast, normal or thorough, got '" + v + "'");
    } else if (a == "--colour" || a == "--color") {
      const std::string& v = value(i);
      if (v == "moved") c.colour = ColourMode::Moved;
      else if (v == "risky") c.colour = ColourMode::Risky;
      else if (v == "none") c.colour = ColourMode::None;
      else die(a + " expects moved, risky or none, got '" + v + "'");
    } else if (a == "--oriented-output") c.oriented_out = value(i);
    else if (a == "--report") c.report = value(i);
    else if (a == "--threads") o.threads = static_cast<int>(at_least_zero(a, integer(a, value(i)), " (0: every core)"));
    else if (a == "--quiet") c.quiet = true;
    else if (a == "--verbose") c.verbose = true;
    else if (!a.empty() && a[0] == '-') die("unknown option " + a + " (see --help)");
    else c.inputs.push_back(a);
  }
  check_files_asked(c);
  if (c.orient && dir_given) die("--orient chooses the print direction itself: leave out --dir");
  if (!c.oriented_out.empty() && !c.orient) die("--oriented-output needs --orient");
  if (creases_given && o.method == SlimmingMethod::Paper)
    die("--max-creases limits the coherent method; the paper's method has no crease limit");
  if (saving_given && o.method == SlimmingMethod::Paper)
    die("--min-saving sets the coherent method's least saving; the paper's method has none");
  if (shape_given && o.method == SlimmingMethod::Paper)
    die("--max-displacement and --allow-stretch shape the coherent method; the paper's method lets the part stretch");

  return c;
}

}  // namespace slim::cli
