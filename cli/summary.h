// What support-slim tells the user about a run: the summary on stdout and the JSON report.
//
//   print_summary(run, verbose); // the summary on stdout: the verdict first, internals if verbose
//   report_json(run);            // every figure of the summary as one flat JSON object
//
// In (RunReport): the files' names, the mesh as read and its welded view, the job (orientation
// and slimming, core/orientation/oriented_slimming.h) and its figures (core/optimizer/slimming_figures.h: support
// estimate, shape cost, budget; mm, mm², mm³, %). Out: text. The report also names the version
// that made it and the settings asked for. The keys are listed in
// docs/usage.md; a key's meaning never changes, new ones may be added.
#pragma once

#include <string>

#include "core/geometry/welded_view.h"
#include "core/optimizer/slimming_figures.h"
#include "core/orientation/oriented_slimming.h"
#include "mesh_io/mesh_io.h"

namespace slim::cli {

struct RunReport {
  std::string in, out;
  bool oriented = false;
  const io::MeshFile* file = nullptr;
  const WeldedView* view = nullptr;
  const OrientedSlimming* job = nullptr;
  const SlimmingOptions* options = nullptr;  // the settings asked for (the report lists those read)
  double scale = 1.0;                          // --scale, applied to the mesh as read
  SlimmingFigures figures;
};

void print_summary(const RunReport& run, bool verbose);
// Every figure of the summary as one flat JSON object, over several lines.
std::string report_json(const RunReport& run);
// The same object on one line (for JSON lines: one run per line).
std::string one_line(const std::string& json);
// `text` as a JSON string, quoted and escaped.
std::string json_string(const std::string& text);
// Writes `text` to `path`; throws std::runtime_error("cannot write <what> <path>") on failure.
void write_text(const std::string& path, const std::string& text, const std::string& what);

}  // namespace slim::cli
