// slim-eval: the measuring steps of tools/evaluate.sh, one subcommand each. Every subcommand
// prints "key=value" lines on stdout (for the script) and exits 1 with a one-line reason on
// stderr on bad input.
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/overhang.h"
#include "gcode_extrusion.h"
#include "print_setup.h"
#include "vcg_adapters/mesh_io.h"

namespace {

const char* kUsage = R"(usage:
  slim-eval prepare IN OUT_BASE [--size MM] [--dir X,Y,Z]
      The part in the print frame: print direction turned onto +Z, scaled so its longest side is
      MM (default 60; 0 keeps the scale), resting on z = 0, centred on the Z axis. Writes
      OUT_BASE.ply. Prints scale, size, diag, vertices, faces.
  slim-eval measure MESH [--angle DEG] [--plate-tolerance MM] [--reference REF] [--stl OUT.stl]
                         [--overhang-ply OUT.ply]
      Risky area and the support proxy (shadow volume, overhang.h) with +Z up, area, volume, bbox;
      with REF (same vertices, e.g. the input of a slimming run) the largest and mean vertex displacement. Writes the mesh as STL, and as a PLY
      whose risky faces are red and the others blue (for pictures).
  slim-eval gcode FILE.gcode
      Filament extruded per feature type; support (incl. interface) in mm and mm^3; the total
      against the slicer's own "filament used [mm]".
  slim-eval threshold DEG
      PrusaSlicer's --support-material-threshold for a self-supporting angle DEG (from the vertical).
)";

[[noreturn]] void die(const std::string& reason) {
  std::cerr << "slim-eval: " << reason << "\n";
  std::exit(1);
}

// Comma-separated numbers ("45", "0,0,1"); exits with a reason unless there are exactly `count`.
std::vector<double> numbers(const std::string& flag, const std::string& text, size_t count) {
  std::vector<double> out;
  std::istringstream in(text);
  std::string part;
  bool ok = !text.empty() && text.back() != ',';
  while (ok && std::getline(in, part, ',')) {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    ok = !part.empty() && *end == '\0' && std::isfinite(v);
    out.push_back(v);
  }
  if (!ok || out.size() != count)
    die(flag + " expects " + (count == 1 ? std::string("a number") : std::to_string(count) + " numbers X,Y,Z") +
        ", got '" + text + "'");
  return out;
}

double number(const std::string& flag, const std::string& text) { return numbers(flag, text, 1)[0]; }

// Positional arguments and "--flag value" options of one subcommand.
struct Args {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;
  const std::string* get(const std::string& flag) const {
    for (const auto& [f, v] : options)
      if (f == flag) return &v;
    return nullptr;
  }
};

Args parse(const std::vector<std::string>& args, const std::vector<std::string>& flags, size_t positional) {
  Args out;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() > 1 && a[0] == '-' && !std::isdigit(static_cast<unsigned char>(a[1]))) {
      bool known = false;
      for (const std::string& f : flags) known = known || f == a;
      if (!known) die("unknown option " + a + " (see --help)");
      if (i + 1 >= args.size()) die(a + " needs a value");
      out.options.emplace_back(a, args[++i]);
    } else {
      out.positional.push_back(a);
    }
  }
  if (out.positional.size() != positional)
    die("expected " + std::to_string(positional) + " file argument(s), got " + std::to_string(out.positional.size()) +
        " (see --help)");
  return out;
}

std::string triple(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(6);
  s << v.x() << "," << v.y() << "," << v.z();
  return s.str();
}

double diagonal(const slim::Surface& s) { return (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm(); }

int prepare(const Args& a) {
  const double size = a.get("--size") ? number("--size", *a.get("--size")) : 60.0;
  if (size < 0) die("--size must not be negative");
  Eigen::Vector3d dir = Eigen::Vector3d::UnitZ();
  if (const std::string* d = a.get("--dir")) dir = Eigen::Vector3d(numbers("--dir", *d, 3).data());
  const slim::Surface in = slim::vcgx::load_surface(a.positional[0]);
  if (in.F.rows() == 0) die(a.positional[0] + " has no faces");
  const slim::eval::PrintFrame frame = slim::eval::to_print_frame(in, dir, size);
  slim::vcgx::save_surface(a.positional[1] + ".ply", frame.surface);
  std::cout << "scale=" << frame.scale << "\nsize=" << triple(frame.size) << "\ndiag=" << frame.size.norm()
            << "\nvertices=" << frame.surface.V.rows() << "\nfaces=" << frame.surface.F.rows() << "\n";
  return 0;
}

int measure(const Args& a) {
  const slim::Surface s = slim::vcgx::load_surface(a.positional[0]);
  slim::OverhangOptions o;  // the part is in the print frame: +Z up
  if (a.get("--angle")) o.alpha_max_deg = number("--angle", *a.get("--angle"));
  o.plate_tolerance = a.get("--plate-tolerance") ? number("--plate-tolerance", *a.get("--plate-tolerance"))
                                                 : 1e-3 * diagonal(s);
  const slim::OverhangReport r = slim::analyse_overhang(s, o);
  std::cout << "risky_area=" << r.risky_area << "\nrisky_faces=" << r.risky_count << "\nshadow_volume=" << r.shadow_volume
            << "\narea=" << r.total_area
            << "\nvolume=" << slim::signed_volume(s) << "\ndiag=" << diagonal(s)
            << "\nbbox_min=" << triple(s.V.colwise().minCoeff().transpose())
            << "\nbbox_max=" << triple(s.V.colwise().maxCoeff().transpose()) << "\n";
  if (const std::string* ref = a.get("--reference")) {
    const slim::Surface r0 = slim::vcgx::load_surface(*ref);
    if (r0.V.rows() != s.V.rows())
      die(*ref + " has " + std::to_string(r0.V.rows()) + " vertices, " + a.positional[0] + " " +
          std::to_string(s.V.rows()) + ": not the same mesh");
    const Eigen::VectorXd moved = (s.V - r0.V).rowwise().norm();
    std::cout << "max_displacement=" << moved.maxCoeff() << "\nmean_displacement=" << moved.mean() << "\n";
  }
  if (const std::string* stl = a.get("--stl")) slim::vcgx::save_surface(*stl, s);
  if (const std::string* ply = a.get("--overhang-ply")) {
    Eigen::VectorXd two_colours(s.F.rows());  // -1: red on the ramp, +1: blue
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) two_colours(f) = r.risky[static_cast<size_t>(f)] ? -1.0 : 0.6;
    slim::vcgx::save_surface(*ply, s, {two_colours, {}});
  }
  return 0;
}

int gcode(const Args& a) {
  std::ifstream in(a.positional[0]);
  if (!in) die("cannot read " + a.positional[0]);
  const slim::eval::GcodeExtrusion g = slim::eval::measure_extrusion(in);
  if (g.total_mm <= 0) die(a.positional[0] + " extrudes nothing: not a sliced G-code file");
  const auto diameter = g.filament_diameter();
  if (!diameter) die(a.positional[0] + " names no filament_diameter (slice with --gcode-comments)");
  const double area = slim::eval::filament_area(*diameter);
  std::cout << "support_mm=" << g.support_mm() << "\nsupport_interface_mm=" << g.type_mm("Support material interface")
            << "\nsupport_mm3=" << g.support_mm() * area << "\ntotal_mm=" << g.total_mm
            << "\ntotal_mm3=" << g.total_mm * area << "\nfilament_diameter=" << *diameter << "\n";
  if (const auto slicer = g.slicer_total_mm()) {
    std::cout << "slicer_total_mm=" << *slicer << "\ntotal_vs_slicer_pct=" << 100.0 * (g.total_mm / *slicer - 1.0)
              << "\n";
  }
  for (const auto& [type, mm] : g.by_type) std::cout << "type[" << type << "]=" << mm << "\n";
  // The settings a reader of the report checks first.
  for (const char* key : {"support_material_threshold", "layer_height", "fill_density", "support_material"}) {
    const auto it = g.settings.find(key);
    if (it != g.settings.end()) std::cout << "setting[" << key << "]=" << it->second << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help") {
    std::cout << kUsage;
    return args.empty() ? 1 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (args[0] == "prepare") return prepare(parse(rest, {"--size", "--dir"}, 2));
    if (args[0] == "measure")
      return measure(parse(rest, {"--angle", "--plate-tolerance", "--reference", "--stl", "--overhang-ply"}, 1));
    if (args[0] == "gcode") return gcode(parse(rest, {}, 1));
    if (args[0] == "threshold") {
      const Args a = parse(rest, {}, 1);
      std::cout << slim::eval::prusa_support_threshold(number("threshold", a.positional[0])) << "\n";
      return 0;
    }
  } catch (const std::exception& e) {
    die(e.what());
  }
  die("unknown subcommand '" + args[0] + "' (see --help)");
}
