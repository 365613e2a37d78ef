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

#include "batch.h"
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
OrientedSlimming run_job(const cli::CliOptions& c, const SlimmingOptions& options, const io::MeshFile& file,
                          const WeldedView& view) {
  if (c.orient && !c.quiet) std::fprintf(stderr, "[orient] searching the print direction\n");
  const std::optional<OrientationOptions> orientation =
      c.orient ? std::optional<OrientationOptions>(with_effort(c.effort)) : std::nullopt;
  OrientedSlimming job = slim_as_asked(view.surface, options, orientation);
  if (!c.oriented_out.empty()) {
    const OverhangReport pose = print_pose_overhang(job.posed, job.orientation, options.print.alpha_max_deg);
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

// The input is a regular readable file of a known format; else a Refusal (bad input file).
void check_input(const std::string& in) {
  std::error_code error;
  const int bad = cli::kExitBadInputFile;
  if (!std::filesystem::exists(in, error)) throw cli::Refusal("cannot read " + in + ": no such file", bad);
  if (std::filesystem::is_directory(in, error)) throw cli::Refusal("cannot read " + in + ": it is a folder, not a mesh file", bad);
  if (access(in.c_str(), R_OK) != 0) throw cli::Refusal("cannot read " + in + ": " + std::strerror(errno), bad);
  try {
    io::format_of(in);
  } catch (const std::exception& e) {
    throw cli::Refusal(e.what(), bad);
  }
}

// The mesh as read, scaled and welded, and the options checked against it: a bad file is a
// Refusal with kExitBadInputFile, a bad option one with kExitUsage, each before any work.
io::MeshFile read_input(const cli::CliOptions& c, const std::string& in, SlimmingOptions& options, WeldedView& view) {
  io::MeshFile file;
  try {
    file = io::read_mesh(in);
    if (c.scale != 1.0) file.surface.V *= c.scale;  // --scale: the units fixed before anything reads them
    view = weld_coincident(file.surface);
    check_slimming_input(view.surface);
  } catch (const std::exception& e) {
    throw cli::Refusal(e.what() + view.vertex_number_note(e.what()), cli::kExitBadInputFile);
  }
  if (!c.features_file.empty()) options.rigid_features = cli::read_face_ids(c.features_file, view.surface.F.rows());
  if (c.features_from_mesh) {
    if (file.face.selected.empty()) throw cli::Refusal(in + " carries no face selection to use as rigid features", cli::kExitUsage);
    options.rigid_features = file.face.selected;
  }
  try {
    validate_slimming_options(options, static_cast<long>(view.surface.F.rows()));
  } catch (const std::exception& e) {
    throw cli::Refusal(e.what(), cli::kExitUsage);
  }
  return file;
}

}  // namespace

namespace slim::cli {

FileRun slim_file(const CliOptions& c, const std::string& in, const std::string& out, bool summary) {
  check_input(in);
  SlimmingOptions options = c.slimming;
  WeldedView view;  // the surface the core computes on (core/geometry/welded_view.h)
  const io::MeshFile file = read_input(c, in, options, view);
  try {
    if (!c.quiet) options.progress = print_progress;
    const OrientedSlimming job = run_job(c, options, file, view);
    const SlimmingResult& r = job.slimming;
    RunReport run{in, out, c.orient, &file, &view, &job, &c.slimming, c.scale, {}};
    run.figures = slimming_figures(job.posed, r, bbox_diagonal(view.surface.V));
    // The files get the input's own vertex list back, moved as the welded view moved.
    const Points V = view.positions_to_input(file.surface.V, r.surface.V);
    const io::FaceExtras faces{c.colour == ColourMode::None ? Eigen::VectorXd() : r.after.quality, r.after.risky};
    if (c.colour == ColourMode::Moved) {
      const Eigen::VectorXd moved = (V - view.positions_to_input(file.surface.V, job.posed.V)).rowwise().norm();
      const double top = run.figures.budget_mm > 0.0 ? run.figures.budget_mm : moved.maxCoeff();
      io::write_mesh(out, io::with_displacement(file, moved, top), V, faces);
    } else
      io::write_mesh(out, file, V, faces);
    if (summary) print_summary(run, c.verbose);
    return {run.figures, r.iterations == 0, r.stop_reason, report_json(run)};
  } catch (const std::exception& e) {
    if (progress_line_open) std::fprintf(stderr, "\n"), progress_line_open = false;
    throw Refusal(e.what() + view.vertex_number_note(e.what()), kExitRunFailed);
  } catch (...) {
    throw Refusal("unexpected internal error (not a std::exception)", kExitRunFailed);
  }
}

}  // namespace slim::cli

int main(int argc, char** argv) {
  const cli::CliOptions c = cli::parse_arguments(std::vector<std::string>(argv + 1, argv + argc));
  if (c.batch()) {
    check_output(c.report, "the report", false);
    if (!std::filesystem::is_directory(c.out_dir)) cli::die("--out-dir " + c.out_dir + " is not a folder");
    return cli::run_batch(c);
  }
  try {
    check_input(c.in);
    check_output(c.out, "the result", true);
    check_output(c.oriented_out, "the oriented part", true);
    check_output(c.report, "the report", false);
    const cli::FileRun run = cli::slim_file(c, c.in, c.out, true);
    if (!c.report.empty()) cli::write_text(c.report, run.report_json, "the report");
  } catch (const cli::Refusal& e) {
    fail(e.what(), e.code);
  }
  return 0;
}
