// support-slim IN -o OUT [options]: Support Slimming without MeshLab. Thin: parse, load, call the
// core, save, summarise. Exits 0 on success, otherwise with a one-line reason and the exit code
// of cli_options.h (bad usage, bad input file, failed run).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli_options.h"
#include "core/geometry/welded_view.h"
#include "core/optimizer/slimming_figures.h"
#include "core/orientation/oriented_slimming.h"
#include "mesh_io/mesh_io.h"
#include "summary.h"

using namespace slim;

namespace {

// Progress on stderr: on a terminal one line rewritten in place; otherwise (a log, a pipe) a
// line per stage, the iterations of a stage counted on its first line only.
bool progress_line_open = false;

bool print_progress(double fraction, const std::string& message) {
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) {
    std::fprintf(stderr, "\r[%3d%%] %-60s", static_cast<int>(100 * fraction), message.c_str());
    progress_line_open = fraction < 1.0;
    if (!progress_line_open) std::fprintf(stderr, "\n");
    return true;
  }
  static std::string stage;
  const std::string now = message.substr(0, message.find("iteration "));
  if (now != stage || fraction >= 1.0) std::fprintf(stderr, "[%3d%%] %s\n", static_cast<int>(100 * fraction), message.c_str());
  stage = now;
  return true;
}

// A reason on a line of its own, even after a progress line left open.
[[noreturn]] void fail(const std::string& reason, int code) {
  if (progress_line_open) std::fprintf(stderr, "\n");
  cli::die(reason, code);
}

// Orientation first (--orient): the part turns rigidly into its print pose and is slimmed there,
// so the slimming's displacement and volume figures count the deformation alone.
OrientedSlimming run_job(const cli::CliOptions& c, const io::MeshFile& file, const WeldedView& view) {
  if (c.orient && !c.quiet) std::fprintf(stderr, "[orient] searching the print direction\n");
  const std::optional<OrientationOptions> orientation =
      c.orient ? std::optional<OrientationOptions>(with_effort(c.effort)) : std::nullopt;
  OrientedSlimming job = slim_as_asked(view.surface, c.slimming, orientation);
  if (!c.oriented_out.empty()) {
    const OverhangReport pose = print_pose_overhang(job.posed, job.orientation, c.slimming.print.alpha_max_deg);
    io::write_mesh(c.oriented_out, file, view.positions_to_input(file.surface.V, job.posed.V), {pose.quality, pose.risky});
  }
  return job;
}

// A file that could not be written would be found missing only after the run: each output's
// folder and format are checked first, and so is the input, so that a bad path costs no work.
void check_output(const std::string& path, const std::string& what, bool mesh) {
  if (path.empty()) return;
  const std::filesystem::path absolute = std::filesystem::absolute(path), folder = absolute.parent_path();
  if (std::filesystem::is_directory(absolute)) cli::die("cannot write " + what + " " + path + ": it is a folder");
  if (mesh) {
    try {
      io::format_of(path);
    } catch (const std::exception& e) {
      cli::die(e.what());
    }
  }
  if (!std::filesystem::is_directory(folder))
    cli::die("cannot write " + what + " " + path + ": its folder " + folder.string() + " does not exist");
  if (access(folder.c_str(), W_OK) != 0)
    cli::die("cannot write " + what + " " + path + ": its folder " + folder.string() + " is not writable (" + std::strerror(errno) + ")");
}

void check_files(const cli::CliOptions& c) {
  std::error_code error;
  const int bad = cli::kExitBadInputFile;
  if (!std::filesystem::exists(c.in, error)) cli::die("cannot read " + c.in + ": no such file", bad);
  if (std::filesystem::is_directory(c.in, error)) cli::die("cannot read " + c.in + ": it is a folder, not a mesh file", bad);
  if (access(c.in.c_str(), R_OK) != 0) cli::die("cannot read " + c.in + ": " + std::strerror(errno), bad);
  try {
    io::format_of(c.in);
  } catch (const std::exception& e) {
    cli::die(e.what(), bad);
  }
  check_output(c.out, "the result", true);
  check_output(c.oriented_out, "the oriented part", true);
  check_output(c.report, "the report", false);
}

// The mesh as read, scaled and welded, and the options checked against it: a bad file exits
// kExitBadInputFile, a bad option kExitUsage, each before any work.
io::MeshFile read_input(cli::CliOptions& c, WeldedView& view) {
  io::MeshFile file;
  try {
    file = io::read_mesh(c.in);
    if (c.scale != 1.0) file.surface.V *= c.scale;  // --scale: the units fixed before anything reads them
    view = weld_coincident(file.surface);
    check_slimming_input(view.surface);
  } catch (const std::exception& e) {
    cli::die(e.what() + view.vertex_number_note(e.what()), cli::kExitBadInputFile);
  }
  if (!c.features_file.empty()) c.slimming.rigid_features = cli::read_face_ids(c.features_file, view.surface.F.rows());
  if (c.features_from_mesh) {
    if (file.face.selected.empty()) cli::die(c.in + " carries no face selection to use as rigid features");
    c.slimming.rigid_features = file.face.selected;
  }
  try {
    validate_slimming_options(c.slimming, static_cast<long>(view.surface.F.rows()));
  } catch (const std::exception& e) {
    cli::die(e.what());
  }
  return file;
}

}  // namespace

int main(int argc, char** argv) {
  cli::CliOptions c = cli::parse_arguments(std::vector<std::string>(argv + 1, argv + argc));
  check_files(c);
  WeldedView view;  // the surface the core computes on (core/geometry/welded_view.h)
  const io::MeshFile file = read_input(c, view);
  try {
    if (!c.quiet) c.slimming.progress = print_progress;
    const OrientedSlimming job = run_job(c, file, view);
    const SlimmingResult& r = job.slimming;
    // The files get the input's own vertex list back, moved as the welded view moved.
    io::write_mesh(c.out, file, view.positions_to_input(file.surface.V, r.surface.V), {r.after.quality, r.after.risky});
    cli::RunReport run{c.in, c.out, c.orient, &file, &view, &job, &c.slimming, c.scale, {}};
    run.figures = slimming_figures(job.posed, r, bbox_diagonal(view.surface.V));
    cli::print_summary(run, c.verbose);
    if (!c.report.empty()) cli::write_report(c.report, run);
  } catch (const std::exception& e) {
    fail(e.what() + view.vertex_number_note(e.what()), cli::kExitRunFailed);
  } catch (...) {
    fail("unexpected internal error (not a std::exception)", cli::kExitRunFailed);
  }
  return 0;
}
