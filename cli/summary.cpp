#include "summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/optimizer/resolution_ladder.h"
#include "core/platform/version.h"
#include "core/print/print_size.h"

namespace slim::cli {

namespace {

// Text folded into lines of at most 100 characters, each after the first indented by `indent`.
std::string wrapped(const std::string& text, size_t indent) {
  std::istringstream words(text);
  std::string out, line, word;
  while (words >> word) {
    if (!line.empty() && indent + line.size() + 1 + word.size() > 100) {
      out += line + "\n" + std::string(indent, ' ');
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line;
}

// What was read and how it is written back: the file's own lists (indexed formats), or the
// vertices STL's separate corners were welded into.
void print_mesh_line(const io::MeshFile& file, const WeldedView& view) {
  const long long nv = file.surface.V.rows(), nf = file.surface.F.rows();
  if (file.format == io::MeshFormat::Stl) {
    std::printf("  mesh            %lld triangles; STL stores each corner apart: %lld corners welded into %lld vertices\n", nf,
                static_cast<long long>(file.stl_corners), nv);
  } else if (file.format == io::MeshFormat::ThreeMf) {
    const io::ThreeMfBuild& b = file.build;
    std::printf("  mesh            %lld vertices, %lld faces: %zu object%s placed by the 3MF build", nv, nf, b.parts.size(),
                b.parts.size() == 1 ? "" : "s");
    if (b.millimetres_per_unit != 1.0) std::printf(", read in mm (the file's unit is %g mm)", b.millimetres_per_unit);
    std::printf(";\n                  a 3MF is written back with the same unit, objects and placements\n");
  } else {
    std::printf("  mesh            %lld vertices, %lld faces, written back as read (same lists, same order)\n", nv, nf);
    if (view.merged() > 0)
      std::printf("                  %lld vertices repeat an earlier one's position: computed as one, they move together\n",
                  static_cast<long long>(view.merged()));
  }
}


// The pose the search chose, in one line.
void print_orientation(const OrientationResult& orientation) {
  const OrientationCandidate& best = orientation.best;
  const double turn = std::acos(std::clamp(best.direction.z(), -1.0, 1.0)) * 180.0 / M_PI;
  std::printf("  orientation     print direction (%.4f, %.4f, %.4f) of the input, turned %.1f deg; %d directions in %.2f s\n",
              best.direction.x(), best.direction.y(), best.direction.z(), turn, orientation.candidates, orientation.seconds);
}

// How the search chose it (--verbose): the model's estimates, the proxies, the best poses.
void print_orientation_details(const OrientationResult& orientation, const SlimmingResult& r) {
  const OrientationCandidate& best = orientation.best;
  if (orientation.as_given.support_estimate && best.support_estimate)
    std::printf("  support model   %.6g (as given) -> %.6g (oriented) mm^3, the support model's choice of pose\n",
                *orientation.as_given.support_estimate, *best.support_estimate);
  std::printf("  support proxy   %.6g (as given) -> %.6g (oriented) -> %.6g (slimmed) mm^3\n",
              orientation.as_given.shadow_volume, r.before.shadow_volume, r.after.shadow_volume);
  std::printf("  risky area      %.6g (as given) -> %.6g (oriented) mm^2\n", orientation.as_given.risky_area, r.before.risky_area);
  std::printf("  best poses      the chosen first, then by the support model's estimate (mm^3, lower is better);\n"
              "                  %d poses judged at one grid phase, %d in full; the proxy only gathered them\n",
              orientation.judged_coarse, orientation.judged_fine);
  auto support = [](const OrientationCandidate& c) { return c.support_estimate ? *c.support_estimate : NAN; };
  for (size_t k = 0; k < orientation.top.size() && k < 5; ++k) {
    const OrientationCandidate& c = orientation.top[k];
    std::printf("    %zu. support %-10.6g %-8s contact %-9.6g proxy %-10.6g dir (%.4f, %.4f, %.4f) %s\n", k + 1, support(c),
                c.stable ? "stands" : "balances", c.contact_area, c.shadow_volume, c.direction.x(), c.direction.y(),
                c.direction.z(), c.origin.c_str());
  }
  std::printf("    as given: support %.6g, %s, proxy %.6g\n", support(orientation.as_given),
              orientation.as_given.stable ? "stands" : "balances", orientation.as_given.shadow_volume);
}

// The support the slicer builds, as the core's support model estimates it (what the run chose by).
void print_support(const SlimmingFigures& f, bool oriented) {
  if (!(f.support_estimate_before_mm3 > 0.0)) return;
  std::printf("  support         %.6g -> %.6g mm^3 (%+.1f%%; the support model's estimate of a slicer's support%s,\n"
              "                  the mean over its grid phases, which the run minimises)\n",
              f.support_estimate_before_mm3, f.support_estimate_after_mm3, f.support_change_pct,
              oriented ? ", in the print pose" : "");
  if (f.support_slicer_phase_before_mm3 > 0.0)
    std::printf("                  at PrusaSlicer's own grid phase: %.6g -> %.6g mm^3 (%+.1f%%; its prediction for these files as placed)\n",
                f.support_slicer_phase_before_mm3, f.support_slicer_phase_after_mm3, f.support_slicer_phase_change_pct);
}

// What the shape paid, next to what the budget allowed.
void print_shape_cost(const SlimmingFigures& f, bool oriented) {
  std::printf("  shape           Hausdorff %.4g mm (%.2f%% of the bbox diagonal%s), volume %+.2f%%, creases %.2f%% of the\n"
              "                  edge length (dihedral angle changed > 10 deg; 99th percentile of the change %.2f deg)\n",
              f.hausdorff_mm, f.hausdorff_pct, oriented ? " as given" : "", f.volume_change_pct, f.crease_share_pct,
              f.crease_p99_deg);
  std::printf("  proportions     extents x %+.2f%%, y %+.2f%%, z %+.2f%%, height %+.2f%%; best-fit affine map %.2f%% from a\n"
              "                  rigid motion; mean displacement %.4g mm (%.2f%% of the bbox diagonal%s); %ld folded faces\n",
              f.extent_change_x_pct, f.extent_change_y_pct, f.extent_change_z_pct, f.height_change_pct, f.affine_departure_pct,
              f.mean_displacement_mm, f.mean_displacement_pct, oriented ? " as given" : "", f.folded_faces);
  if (f.budget_mm > 0.0)
    std::printf("  budget          %.4g mm (%.3g%% of the bbox diagonal%s): no vertex moves further\n", f.budget_mm, f.budget_pct,
                oriented ? " of the part as given" : "");
  else
    std::printf("  budget          none\n");
}

// A JSON number: finite values with 17 significant digits, anything else null.
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

}  // namespace

std::string json_string(const std::string& text) {
  std::string s = "\"";
  for (unsigned char ch : text) {
    if (ch == '"' || ch == '\\') s += '\\', s += static_cast<char>(ch);
    else if (ch < 0x20) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\u%04x", ch);
      s += hex;
    } else s += static_cast<char>(ch);
  }
  return s + "\"";
}

// The verdict, on the summary's first line: what the run did to the support, or why the part
// came back unchanged.
void print_verdict(const RunReport& run) {
  const SlimmingResult& r = run.job->slimming;
  const SlimmingFigures& f = run.figures;
  char text[160];
  std::string what = run.oriented ? "turned into the print pose; " : "";
  if (r.iterations == 0) {
    what += "returned unchanged: " + r.stop_reason;
  } else if (f.support_estimate_before_mm3 > 0.0) {
    std::snprintf(text, sizeof text, "support %.4g -> %.4g mm^3 (%+.1f%%, the support model's estimate)",
                  f.support_estimate_before_mm3, f.support_estimate_after_mm3, f.support_change_pct);
    what += text;
  } else {  // the paper's method is judged by its proxies
    std::snprintf(text, sizeof text, "risky area %.4g -> %.4g mm^2", r.before.risky_area, r.after.risky_area);
    what += text;
  }
  std::printf("support-slim: %s -> %s: %s\n", run.in.c_str(), run.out.c_str(), what.c_str());  // one line, however long
}

// The run's internals, for --verbose: the proxies, the domain and the solver, the ladder.
void print_internals(const RunReport& run) {
  const SlimmingResult& r = run.job->slimming;
  if (run.oriented) {
    print_orientation_details(run.job->orientation, r);
  } else {
    std::printf("  support proxy   %.6g -> %.6g mm^3 (risky faces' footprint x height above the plate)\n",
                r.before.shadow_volume, r.after.shadow_volume);
  }
  const IterationStats& chosen = r.history[static_cast<size_t>(r.iterations)];  // [0] is the input
  std::printf("  volume          %.6g -> %.6g mm^3 (%+.2f%%)\n", run.figures.volume_before_mm3, run.figures.volume_after_mm3,
              run.figures.volume_change_pct);
  std::printf("  AE              %.2f%%   inverted tets %d\n", 100 * chosen.approximation_error, chosen.inverted_tets);
  std::printf("  domain          %d vertices, %d tets; solver %s\n", r.domain_vertices, r.domain_tets,
              r.solver_backend.empty() ? "none (no iteration ran)" : r.solver_backend.c_str());
  std::printf("  resolution      %s\n", wrapped(ladder_line(r), 18).c_str());
}

void print_summary(const RunReport& run, bool verbose) {
  const SlimmingResult& r = run.job->slimming;
  const bool orient = run.oriented;
  print_verdict(run);
  print_shape_cost(run.figures, orient);
  if (const auto warning = print_size_warning(run.view->surface.V))
    std::printf("  units           %s\n", wrapped("WARNING: " + *warning + "; --scale F scales it first", 18).c_str());
  if (run.scale != 1.0) std::printf("  scale           x %g (--scale), the result too\n", run.scale);
  print_mesh_line(*run.file, *run.view);
  print_support(run.figures, orient);
  if (orient) print_orientation(run.job->orientation);
  std::printf("  risky area      %.6g -> %.6g mm^2  (%.2f%% -> %.2f%% of the surface, %.1f%% less)\n",
              r.before.risky_area, r.after.risky_area, 100 * r.before.risky_share(), 100 * r.after.risky_share(),
              r.before.risky_area > 0 ? 100 * (1 - r.after.risky_area / r.before.risky_area) : 0.0);
  std::printf("  iterations      %d in %.2f s (%s)\n", r.iterations, r.seconds, r.stop_reason.c_str());
  std::printf("  displacement    max %.4g mm, mean %.4g mm%s\n", run.figures.max_displacement_mm, run.figures.mean_displacement_mm,
              orient ? " (the deformation alone, in the print pose)" : "");
  if (r.inside_out)
    std::printf("  note            the input is inside out (every normal points inwards): it was computed turned\n"
                "                  over, and %s keeps the input's face orientation\n", run.out.c_str());
  if (run.figures.open_edges > 0) std::printf("  note            %s\n", wrapped(open_mesh_note(run.figures.open_edges), 18).c_str());
  if (verbose) print_internals(run);
}

namespace {

// The settings the run read (the method applied: the paper's method has no limits), as keys of
// the report; a limit that is off is 0, as the CLI takes it.
std::string settings_json(const SlimmingOptions& asked, double scale) {
  const SlimmingOptions o = method_applied(asked);
  const Eigen::Vector3d& d = o.print.direction;
  std::ostringstream os;
  os << ",\n  \"method\": " << json_string(o.method == SlimmingMethod::Paper ? "paper" : "coherent")
     << ",\n  \"alpha_max_deg\": " << json_number(o.print.alpha_max_deg) << ",\n  \"print_direction_given\": ["
     << json_number(d.x()) << ", " << json_number(d.y()) << ", " << json_number(d.z()) << "]"
     << ",\n  \"resolution_given\": " << o.resolution << ",\n  \"one_resolution\": " << (o.ladder.multiples.empty() ? "true" : "false")
     << ",\n  \"max_iterations\": " << o.steps.max_iterations
     << ",\n  \"max_creases_pct\": " << json_number(o.result.max_crease_share_pct.value_or(0.0))
     << ",\n  \"max_displacement_pct\": " << json_number(o.result.max_mean_displacement_pct.value_or(0.0))
     << ",\n  \"min_saving_pct\": " << json_number(o.result.min_support_saving_pct)
     << ",\n  \"allow_stretch\": " << (o.hold_proportions ? "false" : "true") << ",\n  \"scale\": " << json_number(scale);
  return os.str();
}

}  // namespace

std::string report_json(const RunReport& run) {
  const SlimmingFigures& f = run.figures;
  const SlimmingResult& r = run.job->slimming;
  std::vector<std::pair<const char*, double>> numbers = named_figures(f);
  numbers.insert(numbers.end(), {{"iterations_run", r.iterations_run},
                                 {"vertices", static_cast<double>(run.file->surface.V.rows())},
                                 {"faces", static_cast<double>(run.file->surface.F.rows())},
                                 {"domain_vertices", r.domain_vertices},
                                 {"domain_tets", r.domain_tets}});
  std::ostringstream os;
  os << "{\n  \"version\": " << json_string(version()) << ",\n  \"input\": " << json_string(run.in)
     << ",\n  \"output\": " << json_string(run.out) << (run.options ? settings_json(*run.options, run.scale) : "")
     << ",\n  \"oriented\": " << (run.oriented ? "true" : "false") << ",\n  \"unchanged\": " << (r.iterations == 0 ? "true" : "false")
     << ",\n  \"unchanged_reason\": " << json_string(r.iterations == 0 ? r.stop_reason : "")
     << ",\n  \"stop_reason\": " << json_string(r.stop_reason);
  if (run.oriented) {
    const Eigen::Vector3d& d = run.job->orientation.best.direction;
    os << ",\n  \"print_direction\": [" << json_number(d.x()) << ", " << json_number(d.y()) << ", " << json_number(d.z())
       << "]";
  }
  for (const auto& [key, value] : numbers) os << ",\n  \"" << key << "\": " << json_number(value);
  os << "\n}\n";
  return os.str();
}

std::string one_line(const std::string& json) {
  std::string line;  // a raw newline only separates (strings carry theirs escaped): it and its indent become one space
  for (size_t i = 0; i < json.size(); ++i) {
    if (json[i] != '\n') {
      line += json[i];
      continue;
    }
    while (i + 1 < json.size() && json[i + 1] == ' ') ++i;
    if (i + 1 < json.size()) line += ' ';
  }
  return line;
}

void write_text(const std::string& path, const std::string& text, const std::string& what) {
  std::ofstream file(path);
  file << text;
  file.close();
  if (!file) throw std::runtime_error("cannot write " + what + " " + path);
}

}  // namespace slim::cli
