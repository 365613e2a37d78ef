// slim-eval: the measuring steps of eval/studies/part.sh, one subcommand each. Every subcommand
// prints "key=value" lines on stdout (for the script) and exits 1 with a one-line reason on
// stderr on bad input.
#include <cmath>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/geometry/proportions.h"
#include "core/geometry/shape_metrics.h"
#include "core/print/overhang.h"
#include "gcode_extrusion.h"
#include "mesh_io/mesh_io.h"
#include "orient_faces.h"
#include "print_frame.h"
#include "vtk_writer.h"

namespace {

const char* kUsage = R"(usage:
  slim-eval prepare IN OUT_BASE [--size MM] [--dir X,Y,Z] [--orient-faces yes|no]
      The part in the print frame: print direction turned onto +Z, scaled so its longest side is
      MM (default 60; 0 keeps the scale), resting on z = 0, centred on the Z axis. Writes
      OUT_BASE.ply. Prints scale, size, diag, vertices, faces. With --orient-faces yes, faces that
      disagree with their neighbours are turned first, each piece outward (orient_faces.h), and
      flipped_faces says how many; faces that name one vertex twice are left out (dropped_faces).
  slim-eval measure MESH [--angle DEG] [--plate-tolerance MM] [--reference REF] [--stl OUT.stl]
                         [--overhang-ply OUT.ply] [--displacement-vtk OUT.vtk]
      Risky area and the support proxy (shadow volume, overhang.h) with +Z up, area, volume, bbox;
      with REF (same vertices and faces, e.g. the input of a slimming run) the largest and mean
      vertex displacement, the volume change and the crease share (shape_metrics.h). Writes the
      mesh as STL, as a PLY whose risky faces are red and the others blue, and (with REF) as a
      VTK mesh whose point scalar "displacement_mm" is how far each vertex moved (for pictures).
  slim-eval gcode FILE.gcode [--filament-diameter MM]
      Filament extruded per feature type; support (incl. interface) in mm and mm^3; the total
      against the slicer's own "filament used [mm]" (PrusaSlicer). MM is used when the file names
      no filament_diameter (CuraEngine's command line does not).
  slim-eval turn IN OUT --quarter-turns K
      The mesh turned by K x 90 degrees about +Z, exactly (coordinates swapped, no rounding).
  slim-eval toolpath FILE.gcode OUT.vtk [--every N]
      The support extrusions (scalar "support" = 1) and the part's outer walls of every N-th
      layer (0; default N = 2) as VTK line segments, in the slicer's bed frame. Prints their bbox.
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


int prepare(const Args& a) {
  const double size = a.get("--size") ? number("--size", *a.get("--size")) : 60.0;
  if (size < 0) die("--size must not be negative");
  Eigen::Vector3d dir = Eigen::Vector3d::UnitZ();
  if (const std::string* d = a.get("--dir")) dir = Eigen::Vector3d(numbers("--dir", *d, 3).data());
  slim::Surface in = slim::io::load_surface(a.positional[0]);
  if (in.F.rows() == 0) die(a.positional[0] + " has no faces");
  const std::string orient = a.get("--orient-faces") ? *a.get("--orient-faces") : "no";
  if (orient != "yes" && orient != "no") die("--orient-faces expects yes or no, got '" + orient + "'");
  if (orient == "yes") {
    const slim::eval::OrientedFaces o = slim::eval::orient_faces(in);
    if (!o.orientable) die(a.positional[0] + " has a non-orientable piece: its faces cannot all agree");
    in = o.surface;
    std::cout << "flipped_faces=" << o.flipped << "\ndropped_faces=" << o.dropped << "\n";
  }
  const slim::eval::PrintFrame frame = slim::eval::to_print_frame(in, dir, size);
  slim::io::save_surface(a.positional[1] + ".ply", frame.surface);
  std::cout << "scale=" << frame.scale << "\nsize=" << triple(frame.size) << "\ndiag=" << frame.size.norm()
            << "\nvertices=" << frame.surface.V.rows() << "\nfaces=" << frame.surface.F.rows() << "\n";
  return 0;
}

int measure(const Args& a) {
  const slim::Surface s = slim::io::load_surface(a.positional[0]);
  slim::PrintSetup o;  // the part is in the print frame: +Z up
  if (a.get("--angle")) o.alpha_max_deg = number("--angle", *a.get("--angle"));
  if (a.get("--plate-tolerance")) o.plate = slim::PlateRule::within(number("--plate-tolerance", *a.get("--plate-tolerance")));
  const slim::OverhangReport r = slim::analyse_overhang(s, o);
  std::cout << "risky_area=" << r.risky_area << "\nrisky_faces=" << r.risky_count << "\nshadow_volume=" << r.shadow_volume
            << "\narea=" << r.total_area
            << "\nvolume=" << slim::signed_volume(s) << "\ndiag=" << slim::bbox_diagonal(s.V)
            << "\nbbox_min=" << triple(s.V.colwise().minCoeff().transpose())
            << "\nbbox_max=" << triple(s.V.colwise().maxCoeff().transpose()) << "\n";
  if (const std::string* ref = a.get("--reference")) {
    const slim::Surface r0 = slim::io::load_surface(*ref);
    if (r0.V.rows() != s.V.rows())
      die(*ref + " has " + std::to_string(r0.V.rows()) + " vertices, " + a.positional[0] + " " +
          std::to_string(s.V.rows()) + ": not the same mesh");
    const Eigen::VectorXd moved = (s.V - r0.V).rowwise().norm();
    std::cout << "max_displacement=" << moved.maxCoeff() << "\nmean_displacement=" << moved.mean() << "\n";
    const slim::ShapeChange c = slim::shape_change(r0, s);
    if (c.volume_defined) std::cout << "volume_change_pct=" << c.volume_change_pct << "\n";
    std::cout << "crease_share_pct=" << c.crease_share_pct << "\ncrease_p99_deg=" << c.crease_p99_deg
              << "\nmax_crease_deg=" << c.max_crease_deg << "\ninterior_edges=" << c.interior_edges << "\n";
    const slim::Proportions p = slim::proportions(r0, s.V, Eigen::Vector3d::UnitZ());  // the print frame: +Z up
    std::cout << "extent_change_x_pct=" << p.extent_change_pct.x() << "\nextent_change_y_pct=" << p.extent_change_pct.y()
              << "\nextent_change_z_pct=" << p.extent_change_pct.z() << "\nheight_change_pct=" << p.height_change_pct
              << "\naffine_departure_pct=" << p.affine_departure_pct << "\nfolded_faces=" << p.folded_faces << "\n";
    if (const std::string* vtk = a.get("--displacement-vtk")) slim::eval::write_vtk_mesh(*vtk, s, "displacement_mm", moved);
  } else if (a.get("--displacement-vtk")) {
    die("--displacement-vtk needs --reference");
  }
  if (const std::string* stl = a.get("--stl")) slim::io::save_surface(*stl, s);
  if (const std::string* ply = a.get("--overhang-ply")) {
    Eigen::VectorXd two_colours(s.F.rows());  // -1: red on the ramp, +1: blue
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) two_colours(f) = r.risky[static_cast<size_t>(f)] ? -1.0 : 0.6;
    slim::io::save_surface(*ply, s, {two_colours, {}});
  }
  return 0;
}

int gcode(const Args& a) {
  std::ifstream in(a.positional[0]);
  if (!in) die("cannot read " + a.positional[0]);
  const slim::eval::GcodeExtrusion g = slim::eval::measure_extrusion(in);
  if (g.total_mm <= 0) die(a.positional[0] + " extrudes nothing: not a sliced G-code file");
  std::optional<double> diameter = g.filament_diameter();
  if (!diameter && a.get("--filament-diameter")) diameter = number("--filament-diameter", *a.get("--filament-diameter"));
  if (!diameter || !(*diameter > 0))
    die(a.positional[0] + " names no filament_diameter (slice PrusaSlicer with --gcode-comments, or give --filament-diameter)");
  const double area = slim::eval::filament_area(*diameter);
  std::cout << "support_mm=" << g.support_mm() << "\nsupport_interface_mm=" << g.support_interface_mm()
            << "\nsupport_interface_mm3=" << g.support_interface_mm() * area << "\nsupport_mm3=" << g.support_mm() * area << "\ntotal_mm=" << g.total_mm
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

int turn(const Args& a) {
  const std::string* k_text = a.get("--quarter-turns");
  if (!k_text) die("turn needs --quarter-turns K");
  const double k_value = number("--quarter-turns", *k_text);
  if (k_value != std::floor(k_value)) die("--quarter-turns expects a whole number, got '" + *k_text + "'");
  const int k = ((static_cast<int>(k_value) % 4) + 4) % 4;
  slim::Surface s = slim::io::load_surface(a.positional[0]);
  for (int i = 0; i < k; ++i) {  // (x, y) -> (-y, x): a quarter turn counter-clockwise seen from +Z
    const Eigen::VectorXd x = s.V.col(0);
    s.V.col(0) = -s.V.col(1);
    s.V.col(1) = x;
  }
  slim::io::save_surface(a.positional[1], s);
  return 0;
}

int toolpath(const Args& a) {
  const long every = a.get("--every") ? std::lround(number("--every", *a.get("--every"))) : 2;
  if (every < 1) die("--every must be at least 1");
  std::ifstream in(a.positional[0]);
  if (!in) die("cannot read " + a.positional[0]);
  slim::eval::Segments segs;
  double last_z = -1e300;
  long layer = -1;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  slim::eval::measure_extrusion(in, [&](const slim::eval::ExtrusionMove& m) {
    if (m.to[2] != last_z) ++layer, last_z = m.to[2];
    const bool support = slim::eval::is_support_type(m.type);
    const bool wall = m.type == "External perimeter" || m.type == "WALL-OUTER";
    if (!support && !(wall && layer % every == 0)) return;
    segs.from.emplace_back(m.from[0], m.from[1], m.from[2]);
    segs.to.emplace_back(m.to[0], m.to[1], m.to[2]);
    segs.value.push_back(support ? 1.0 : 0.0);
    lo = lo.cwiseMin(segs.from.back()).cwiseMin(segs.to.back());
    hi = hi.cwiseMax(segs.from.back()).cwiseMax(segs.to.back());
  });
  if (segs.from.empty()) die(a.positional[0] + " has no outer walls and no support: not a sliced G-code file");
  slim::eval::write_vtk_segments(a.positional[1], segs, "support");
  std::cout << "segments=" << segs.from.size() << "\nbbox_min=" << triple(lo) << "\nbbox_max=" << triple(hi) << "\n";
  return 0;
}

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help") {
    std::cout << kUsage;
    return args.empty() ? 1 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (args[0] == "prepare") return prepare(parse(rest, {"--size", "--dir", "--orient-faces"}, 2));
    if (args[0] == "measure")
      return measure(parse(rest, {"--angle", "--plate-tolerance", "--reference", "--stl", "--overhang-ply", "--displacement-vtk"}, 1));
    if (args[0] == "gcode") return gcode(parse(rest, {"--filament-diameter"}, 1));
    if (args[0] == "turn") return turn(parse(rest, {"--quarter-turns"}, 2));
    if (args[0] == "toolpath") return toolpath(parse(rest, {"--every"}, 2));
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
