// The bad inputs: meshes and settings that must never crash, hang or exhaust memory.
// Each ends either in a valid result with sane statistics or in a refusal whose message says what
// was wrong and what to change. The core tests, the plugin harness, the meshlabserver tests, the
// CLI tests and the fuzz seed corpus all run these same cases.
//
// bad_inputs() -> the catalogue, in a fixed order.
// bad_files() -> the file-level catalogue: malformed mesh files the CLI's readers must
//   refuse with one line naming the file and what is wrong (bad_files.cpp).
// slimming_result_problem(input, options, result) -> "" when a result is sane, else what is not:
//   finite positions, the input's faces, displacements that match the positions, no vertex below
//   the plate, within the deviation budget, risky area not increased, statistics that re-measure.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/geometry/surface.h"
#include "core/optimizer/slimming.h"
#include "core/orientation/orientation.h"

namespace slim::test {

struct BadInput {
  std::string name;  // an identifier: test names, corpus file names
  std::string what;  // one line for people
  Surface surface;
  // Only fields the MeshLab dialog offers (the plugin runner maps them onto its parameters), and
  // rigid_features, which the plugin takes from the face selection.
  SlimmingOptions options;
  bool preserve_selection = false;  // the plugin's 'Preserve selection as rigid features'
  // Support Slimming: empty = a valid result is expected; else the refusal contains `refusal`
  // (what was wrong) and `advice` (what to change), both compared case-insensitively.
  std::string refusal, advice;
  // The plugin refuses before the core is asked (a MeshLab-only rule); same convention.
  std::string plugin_refusal;
  // Overhang Analysis: empty = it succeeds; else its refusal contains this.
  std::string analysis_refusal;
  bool inside_out = false;     // expected to be detected and computed turned over
  double risky_before = -1.0;  // when >= 0: the risky area (mm²) the run must see in the input
  bool meshlabserver = false;  // part of the subset that also runs through the real meshlabserver
};

std::vector<BadInput> bad_inputs();

// A malformed mesh file. The readers (vcg_adapters/mesh_io.h) refuse it with
// std::runtime_error("cannot read <path>: <why>"), and the CLI with one line holding that, before
// they allocate anything for the counts it claims; the CLI tests, the robustness test and the
// readers' fuzz seed corpus run every one.
struct BadFile {
  std::string name;       // an identifier: test names, file names (<name>.<extension>)
  std::string what;       // one line for people
  std::string extension;  // ply, stl, obj or off (or another, which no reader takes)
  std::string bytes;      // the file
  std::string refusal;    // the reason contains this, compared case-insensitively
};

std::vector<BadFile> bad_files();
void PrintTo(const BadFile& f, std::ostream* os);

// gtest prints a parameter through this (its name) instead of its bytes.
void PrintTo(const BadInput& c, std::ostream* os);

std::string slimming_result_problem(const Surface& input, const SlimmingOptions& options,
                                    const SlimmingResult& result);

// Writes an ASCII PLY of the surface, as MeshLab and the CLI read it; unlike VCG's exporter it
// writes NaN and infinite coordinates too ("nan", "inf"). Throws std::runtime_error on failure.
void write_ascii_ply(const std::string& path, const Surface& s);

// What Print Orientation at its Fast effort should do with `s` at `alpha_max_deg`, by the core
// (on the welded view, core/geometry/welded_view.h, as the filter computes): its result; when the core refuses, a default result and the refusal (std::invalid_argument's
// message) in `refusal`, which is empty otherwise.
OrientationResult fast_orientation(const Surface& s, double alpha_max_deg, std::string& refusal);

// True when `text` contains `part`, ignoring case.
bool mentions(const std::string& text, const std::string& part);

}  // namespace slim::test
