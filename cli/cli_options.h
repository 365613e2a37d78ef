// The command line of support-slim: what the user asked for, parsed and checked.
//
//   CliOptions c = parse_arguments(args);   // args: argv[1..]
//
// In: the arguments as given. Out: the files, the switches and the core's SlimmingOptions.
// A bad argument ends the program through die(): exit status kExitUsage and one line on stderr
// naming the flag and what it expects; -h prints the usage and exits 0.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "core/optimizer/slimming.h"
#include "core/orientation/orientation.h"

namespace slim::cli {

// What the colours of OUT say (--colour): how far each vertex moved (a vertex colour ramp, where
// the format holds vertex colours and IN has none of its own) and the still-risky faces (face
// colours); the still-risky faces alone; or nothing the run adds.
enum class ColourMode { Moved, Risky, None };

struct CliOptions {
  std::string in, out;              // the input mesh and where the result goes (one file)
  std::vector<std::string> inputs;  // every input mesh given, in order
  std::string out_dir;              // --out-dir: a batch, each input to DIR/<stem>_slimmed.<ext>
  std::string features_file;        // rigid features: face ids, one file
  std::string oriented_out;         // with --orient: the oriented part before slimming
  std::string report;               // --report: the figures as JSON
  double scale = 1.0;               // --scale: IN's positions times this, first (> 0)
  bool features_from_mesh = false, quiet = false, orient = false, verbose = false;
  OrientationEffort effort = OrientationEffort::Normal;
  ColourMode colour = ColourMode::Moved;
  SlimmingOptions slimming;

  bool batch() const { return !out_dir.empty(); }
};

// The exit codes (docs/usage.md). Bad usage: an unknown flag, a value out of its range, an output
// path that cannot be written; bad input file: the mesh is missing, unreadable, not a mesh of a
// known format, or one the run refuses (no faces, non-finite coordinates, faces not consistently
// oriented, zero extent); a failed run: anything after that (the memory guard, a write error).
inline constexpr int kExitRunFailed = 1, kExitUsage = 2, kExitBadInputFile = 3;

// One line on stderr ("support-slim: " and the reason), then exit with `code`.
[[noreturn]] void die(const std::string& reason, int code = kExitUsage);

// The same reason and code, thrown where one file of a batch may fail and the others go on.
struct Refusal : std::runtime_error {
  int code;
  Refusal(const std::string& reason, int exit_code) : std::runtime_error(reason), code(exit_code) {}
};

CliOptions parse_arguments(const std::vector<std::string>& args);

// The face ids of a features file (white-space separated, 0-based) as a mask over `faces`.
std::vector<bool> read_face_ids(const std::string& path, long long faces);

}  // namespace slim::cli
