// support-slim IN -o OUT [options]: Support Slimming without MeshLab. Thin: parse, load, call the
// core, save, summarise. Exits 0 on success, 1 with a one-line reason otherwise.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>


#include "core/slimming.h"
#include "vcg_adapters/mesh_io.h"

namespace {

const char* kUsage = R"(usage: support-slim IN -o OUT [options]

Reshapes a mesh so that it needs less support material when 3D printed (local/global
minimal-rotation optimizer). Reads and writes PLY, STL, OBJ and OFF; OUT is written in the input's
frame (no rescaling, no recentring). A PLY output carries face quality n.d + sin(alpha_max)
(negative = still risky), its colour ramp, and the still-risky faces as selected.

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

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string in, out, features_file;
  bool features_from_mesh = false, quiet = false;
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
    else if (a == "--dir") o.print_direction = vector3(a, value(i));
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
    else if (a == "--threads") o.threads = integer(a, value(i));
    else if (a == "--quiet") quiet = true;
    else if (!a.empty() && a[0] == '-') die("unknown option " + a + " (see --help)");
    else if (in.empty()) in = a;
    else die("more than one input mesh given: " + in + " and " + a);
  }
  if (in.empty()) die("no input mesh given (see --help)");
  if (out.empty()) die("no output given: use -o OUT");

  try {
    slim::vcgx::FaceExtras extras;
    const slim::Surface mesh = slim::vcgx::load_surface(in, &extras);
    if (!features_file.empty()) o.rigid_features = read_face_ids(features_file, mesh.F.rows());
    if (features_from_mesh) {
      if (extras.selected.empty()) die(in + " carries no face selection to use as rigid features");
      o.rigid_features = extras.selected;
    }
    if (!quiet) {
      o.progress = [](double fraction, const std::string& message) {
        std::fprintf(stderr, "\r[%3d%%] %-60s", static_cast<int>(100 * fraction), message.c_str());
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        return true;
      };
    }
    const slim::SlimmingResult r = slim::slim_supports(mesh, o);
    slim::vcgx::save_surface(out, r.surface, {r.after.quality, r.after.risky});

    const slim::IterationStats& last = r.history.back();
    std::printf("support-slim: %s -> %s\n", in.c_str(), out.c_str());
    std::printf("  risky area      %.6g -> %.6g mm^2  (%.2f%% -> %.2f%% of the surface, %.1f%% less)\n",
                r.before.risky_area, r.after.risky_area, 100 * r.before.risky_share(), 100 * r.after.risky_share(),
                r.before.risky_area > 0 ? 100 * (1 - r.after.risky_area / r.before.risky_area) : 0.0);
    std::printf("  iterations      %d in %.2f s (%s)\n", r.iterations, r.seconds, r.stop_reason.c_str());
    std::printf("  displacement    max %.4g mm, mean %.4g mm\n", last.max_displacement, last.mean_displacement);
    std::printf("  volume          %.6g -> %.6g mm^3 (%+.2f%%)\n", r.volume_before, r.volume_after,
                r.volume_before != 0 ? 100 * (r.volume_after / r.volume_before - 1) : 0.0);
    std::printf("  AE              %.2f%%   inverted tets %d\n", 100 * last.approximation_error, last.inverted_tets);
    std::printf("  domain          %d vertices, %d tets; solver %s\n", r.domain_vertices, r.domain_tets,
                r.solver_backend.c_str());
    if (r.inside_out)
      std::printf("  note            the input is inside out (every normal points inwards): it was computed turned\n"
                  "                  over, and %s keeps the input's face orientation\n", out.c_str());
  } catch (const std::exception& e) {
    die(e.what());
  } catch (...) {
    die("unexpected internal error (not a std::exception)");
  }
  return 0;
}
