// support-slim IN... --out-dir DIR: each input in turn, past any that fails, then one table.
//
//   int status = run_batch(options);   // options.batch(): options.inputs and options.out_dir
//
// In: the parsed command line. Each input IN goes to DIR/<IN's name without extension>_slimmed.<IN's
// extension> through slim_file (support_slim.cpp, the same run as for one file, summary line by
// line as each finishes). Out: the table on stdout (file, support before -> after by the model,
// the shape figures, the status: done, unchanged and why, or failed and why); with --report, one
// JSON object per line and file, a failure's carrying "status": "failed", "error" and
// "exit_code". Returns 0 when every file was done, kExitRunFailed when any failed.
#pragma once

#include <string>

#include "cli_options.h"
#include "core/optimizer/slimming_figures.h"

namespace slim::cli {

// What one file's run gives the batch.
struct FileRun {
  SlimmingFigures figures;
  bool unchanged = false;
  std::string stop_reason;
  std::string report_json;  // summary.h's report_json
};

// One file slimmed as support-slim slims one (support_slim.cpp); throws Refusal (reason and exit
// code) when the file is refused or the run fails. `summary`: print the summary on stdout.
FileRun slim_file(const CliOptions& c, const std::string& in, const std::string& out, bool summary);

// Where a batch writes `in`: DIR/<stem>_slimmed.<extension>.
std::string batch_output(const std::string& out_dir, const std::string& in);

int run_batch(const CliOptions& c);

}  // namespace slim::cli
