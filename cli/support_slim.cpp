// support-slim IN -o OUT [options]: Support Slimming without MeshLab. Thin: parse, load, call the
// core, save, summarise. Exits 0 on success, 1 with a one-line reason otherwise.
#include <cstdio>
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

bool print_progress(double fraction, const std::string& message) {
  std::fprintf(stderr, "\r[%3d%%] %-60s", static_cast<int>(100 * fraction), message.c_str());
  if (fraction >= 1.0) std::fprintf(stderr, "\n");
  return true;
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

// A report that could not be written would be found missing only after the run and after OUT was
// written: its folder is checked first.
void check_report_folder(const std::string& report) {
  if (report.empty()) return;
  const std::filesystem::path folder = std::filesystem::absolute(report).parent_path();
  if (!std::filesystem::is_directory(folder) || access(folder.c_str(), W_OK) != 0)
    cli::die("cannot write the report " + report + ": its folder " + folder.string() + " does not exist or is not writable");
}

}  // namespace

int main(int argc, char** argv) {
  cli::CliOptions c = cli::parse_arguments(std::vector<std::string>(argv + 1, argv + argc));
  check_report_folder(c.report);
  WeldedView view;  // the surface the core computes on (core/geometry/welded_view.h)
  try {
    const io::MeshFile file = io::read_mesh(c.in);
    view = weld_coincident(file.surface);
    if (!c.features_file.empty()) c.slimming.rigid_features = cli::read_face_ids(c.features_file, view.surface.F.rows());
    if (c.features_from_mesh) {
      if (file.face.selected.empty()) cli::die(c.in + " carries no face selection to use as rigid features");
      c.slimming.rigid_features = file.face.selected;
    }
    if (!c.quiet) c.slimming.progress = print_progress;
    const OrientedSlimming job = run_job(c, file, view);
    const SlimmingResult& r = job.slimming;
    // The files get the input's own vertex list back, moved as the welded view moved.
    io::write_mesh(c.out, file, view.positions_to_input(file.surface.V, r.surface.V), {r.after.quality, r.after.risky});
    cli::RunReport run{c.in, c.out, c.orient, &file, &view, &job, {}};
    run.figures = slimming_figures(job.posed, r, bbox_diagonal(view.surface.V));
    cli::print_summary(run);
    if (!c.report.empty()) cli::write_report(c.report, run);
  } catch (const std::exception& e) {
    cli::die(e.what() + view.vertex_number_note(e.what()));
  } catch (...) {
    cli::die("unexpected internal error (not a std::exception)");
  }
  return 0;
}
