// support-slim IN -o OUT [options]: Support Slimming without MeshLab. Thin: parse, load, call the
// core, save, summarise. Exits 0 on success, 1 with a one-line reason otherwise.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>


#include "core/oriented_slimming.h"
#include "core/slimming.h"
#include "core/welded_view.h"
#include "vcg_adapters/mesh_io.h"

namespace {

const char* kUsage = R"(usage: support-slim IN -o OUT [options]

Reshapes a mesh so that it needs less support material when 3D printed (local/global
minimal-rotation optimizer). Reads and writes PLY, STL, OBJ and OFF. OUT has IN's vertex list and
face list in IN's order: nothing is welded, dropped or reordered (STL, which stores each
triangle's corners apart, is welded when read), and IN's vertex colours, texture coordinates,
vertex quality and selection pass through; vertex normals too, recomputed where a vertex moved.
The run replaces three face attributes: face quality becomes n.d + sin(alpha_max) (negative =
still risky; PLY), face colour its ramp (PLY, OFF, STL), and the face selection the still-risky
faces (PLY). OUT is in the input's frame (no rescaling, no recentring), or with --orient in the
print pose the search chose. See docs/files-and-attributes.md.

options:
  -o, --output FILE        where to write the result (required)
  --angle DEG              self-supporting angle from the vertical, [0, 90)       [45]
  --dir X,Y,Z              print direction                                     [0,0,1]
  --plate-tolerance MM     faces this close to the lowest point rest on the plate
                                                                  [1e-3 of the bbox diagonal]
  --resolution N           voxel cells along the longest side                      [24]
  --domain voxel|tetgen    the tetrahedral domain                               [voxel]
  --method coherent|paper  coherent (default) or the paper's method as written [coherent]
  --iterations N           iteration limit; 0 embeds and writes back only          [40]
  --max-deviation PCT      deviation budget, % of the bbox diagonal (0: none)       [5]
  --max-k K                largest number of K-means proxies per tet                 [8]
  --features FILE          rigid features: a text file of face ids (0-based)
  --features-from-mesh     rigid features: the faces selected in IN (PLY face flags)
  --orient                 first turn the part into the print pose that needs the least support
                           (estimated), then slim it there; OUT is in that pose, +Z up, resting
                           on z = 0, and the displacement counts only the deformation
  --orient-effort fast|normal|thorough
                           how many directions the orientation search tries         [normal]
  --oriented-output FILE   with --orient: also write the oriented part before slimming
  --threads N              OpenMP threads (the result does not depend on it)
  --quiet                  no progress on stderr
  -h, --help               this text
)";

[[noreturn]] void die(const std::string& reason) {
  std::cerr << "support-slim: " << reason << "\n";
  std::exit(1);
}

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

Eigen::Vector3d vector3(const std::string& flag, const std::string& text) {
  std::stringstream ss(text);
  std::string part;
  std::vector<double> v;
  while (std::getline(ss, part, ',')) v.push_back(number(flag, part));
  if (v.size() != 3) die(flag + " expects X,Y,Z, got '" + text + "'");
  return {v[0], v[1], v[2]};
}

std::vector<bool> read_face_ids(const std::string& path, Eigen::Index faces) {
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

// What was read and how it is written back: the file's own lists (indexed formats), or the
// vertices STL's separate corners were welded into.
void print_mesh_line(const slim::vcgx::MeshFile& file, const slim::WeldedView& view) {
  const long long nv = file.surface.V.rows(), nf = file.surface.F.rows();
  if (file.format == slim::vcgx::MeshFormat::Stl) {
    std::printf("  mesh            %lld triangles; STL stores each corner apart: %lld corners welded into %lld vertices\n", nf,
                static_cast<long long>(file.stl_corners), nv);
  } else {
    std::printf("  mesh            %lld vertices, %lld faces, written back as read (same lists, same order)\n", nv, nf);
    if (view.merged() > 0)
      std::printf("                  %lld vertices repeat an earlier one's position: computed as one, they move together\n",
                  static_cast<long long>(view.merged()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string in, out, features_file, oriented_out;
  bool features_from_mesh = false, quiet = false, orient = false, dir_given = false;
  slim::OrientationEffort effort = slim::OrientationEffort::Normal;
  slim::SlimmingOptions o;
  auto value = [&](size_t& i) -> const std::string& {
    if (i + 1 >= args.size()) die(args[i] + " needs a value");
    return args[++i];
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (a == "-o" || a == "--output") out = value(i);
    else if (a == "--angle") o.alpha_max_deg = number(a, value(i));
    else if (a == "--dir") o.print_direction = vector3(a, value(i)), dir_given = true;
    else if (a == "--plate-tolerance") o.plate_tolerance = number(a, value(i));
    else if (a == "--resolution") o.resolution = integer(a, value(i));
    else if (a == "--domain") {
      const std::string& v = value(i);
      if (v == "voxel") o.domain = slim::DomainKind::Voxel;
      else if (v == "tetgen") o.domain = slim::DomainKind::TetGen;
      else die("--domain expects voxel or tetgen, got '" + v + "'");
    } else if (a == "--method") {
      const std::string& v = value(i);
      if (v == "coherent") o.method = slim::SlimmingMethod::Coherent;
      else if (v == "paper") o.method = slim::SlimmingMethod::Paper;
      else die("--method expects coherent or paper, got '" + v + "'");
    } else if (a == "--iterations") o.max_iterations = integer(a, value(i));
    else if (a == "--max-deviation") o.max_deviation_pct = number(a, value(i));
    else if (a == "--max-k") o.max_k = integer(a, value(i));
    else if (a == "--features") features_file = value(i);
    else if (a == "--features-from-mesh") features_from_mesh = true;
    else if (a == "--orient") orient = true;
    else if (a == "--orient-effort") {
      const std::string& v = value(i);
      if (v == "fast") effort = slim::OrientationEffort::Fast;
      else if (v == "normal") effort = slim::OrientationEffort::Normal;
      else if (v == "thorough") effort = slim::OrientationEffort::Thorough;
      else die("--orient-effort expects fast, normal or thorough, got '" + v + "'");
    } else if (a == "--oriented-output") oriented_out = value(i);
    else if (a == "--threads") o.threads = integer(a, value(i));
    else if (a == "--quiet") quiet = true;
    else if (!a.empty() && a[0] == '-') die("unknown option " + a + " (see --help)");
    else if (in.empty()) in = a;
    else die("more than one input mesh given: " + in + " and " + a);
  }
  if (in.empty()) die("no input mesh given (see --help)");
  if (out.empty()) die("no output given: use -o OUT");
  if (orient && dir_given) die("--orient chooses the print direction itself: leave out --dir");
  if (!oriented_out.empty() && !orient) die("--oriented-output needs --orient");

  slim::WeldedView view;  // the surface the core computes on (core/welded_view.h)
  try {
    const slim::vcgx::MeshFile file = slim::vcgx::read_mesh(in);
    view = slim::weld_coincident(file.surface);
    const slim::Surface& mesh = view.surface;
    if (!features_file.empty()) o.rigid_features = read_face_ids(features_file, mesh.F.rows());
    if (features_from_mesh) {
      if (file.face.selected.empty()) die(in + " carries no face selection to use as rigid features");
      o.rigid_features = file.face.selected;
    }
    if (!quiet) {
      o.progress = [](double fraction, const std::string& message) {
        std::fprintf(stderr, "\r[%3d%%] %-60s", static_cast<int>(100 * fraction), message.c_str());
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        return true;
      };
    }
    // Orientation first: the part turns rigidly into its print pose and is slimmed there, so the
    // slimming's displacement and volume figures count the deformation alone. The core computes on
    // the welded view; the files get the input's own vertex list back.
    slim::OrientedSlimming job;
    if (orient) {
      if (!quiet) std::fprintf(stderr, "[orient] searching the print direction\n");
      job = slim::slim_in_best_pose(mesh, o, slim::with_effort(effort));
      if (!oriented_out.empty()) {
        const slim::OverhangReport pose = slim::print_pose_overhang(job.posed, job.orientation, o.alpha_max_deg);
        slim::vcgx::write_mesh(oriented_out, file, view.positions_to_input(file.surface.V, job.posed.V),
                               {pose.quality, pose.risky});
      }
    } else {
      job.slimming = slim::slim_supports(mesh, o);
    }
    const slim::SlimmingResult& r = job.slimming;
    const slim::OrientationResult& orientation = job.orientation;
    slim::vcgx::write_mesh(out, file, view.positions_to_input(file.surface.V, r.surface.V), {r.after.quality, r.after.risky});

    const slim::IterationStats& last = r.history.back();
    std::printf("support-slim: %s -> %s\n", in.c_str(), out.c_str());
    print_mesh_line(file, view);
    if (orient) {
      const slim::OrientationCandidate& best = orientation.best;
      const double turn = std::acos(std::clamp(best.direction.z(), -1.0, 1.0)) * 180.0 / M_PI;
      std::printf("  orientation     print direction (%.4f, %.4f, %.4f) of the input, turned %.1f deg; %d directions in %.2f s\n",
                  best.direction.x(), best.direction.y(), best.direction.z(), turn, orientation.candidates,
                  orientation.seconds);
      std::printf("  support proxy   %.6g (as given) -> %.6g (oriented) -> %.6g (slimmed) mm^3\n",
                  orientation.as_given.shadow_volume, r.before.shadow_volume, r.after.shadow_volume);
      std::printf("  risky area      %.6g (as given) -> %.6g (oriented) mm^2\n", orientation.as_given.risky_area,
                  r.before.risky_area);
      std::printf("  best poses      score = support proxy - %.3g mm x plate contact (mm^3; lower is better)\n",
                  orientation.contact_bonus_height);
      for (size_t k = 0; k < orientation.top.size() && k < 5; ++k) {
        const slim::OrientationCandidate& c = orientation.top[k];
        std::printf("    %zu. score %-11.6g proxy %-11.6g risky %-10.6g contact %-10.6g dir (%.4f, %.4f, %.4f) %s\n", k + 1,
                    c.score, c.shadow_volume, c.risky_area, c.contact_area, c.direction.x(), c.direction.y(),
                    c.direction.z(), c.origin.c_str());
      }
      std::printf("    as given: score %.6g\n", orientation.as_given.score);
    } else {
      std::printf("  support proxy   %.6g -> %.6g mm^3 (risky faces' footprint x height above the plate)\n",
                  r.before.shadow_volume, r.after.shadow_volume);
    }
    std::printf("  risky area      %.6g -> %.6g mm^2  (%.2f%% -> %.2f%% of the surface, %.1f%% less)\n",
                r.before.risky_area, r.after.risky_area, 100 * r.before.risky_share(), 100 * r.after.risky_share(),
                r.before.risky_area > 0 ? 100 * (1 - r.after.risky_area / r.before.risky_area) : 0.0);
    std::printf("  iterations      %d in %.2f s (%s)\n", r.iterations, r.seconds, r.stop_reason.c_str());
    std::printf("  displacement    max %.4g mm, mean %.4g mm%s\n", last.max_displacement, last.mean_displacement,
                orient ? " (the deformation alone, in the print pose)" : "");
    std::printf("  volume          %.6g -> %.6g mm^3 (%+.2f%%)\n", r.volume_before, r.volume_after,
                r.volume_before != 0 ? 100 * (r.volume_after / r.volume_before - 1) : 0.0);
    std::printf("  AE              %.2f%%   inverted tets %d\n", 100 * last.approximation_error, last.inverted_tets);
    std::printf("  domain          %d vertices, %d tets; solver %s\n", r.domain_vertices, r.domain_tets,
                r.solver_backend.empty() ? "none (no iteration ran)" : r.solver_backend.c_str());
    if (r.inside_out)
      std::printf("  note            the input is inside out (every normal points inwards): it was computed turned\n"
                  "                  over, and %s keeps the input's face orientation\n", out.c_str());
  } catch (const std::exception& e) {
    die(e.what() + view.vertex_number_note(e.what()));
  } catch (...) {
    die("unexpected internal error (not a std::exception)");
  }
  return 0;
}
