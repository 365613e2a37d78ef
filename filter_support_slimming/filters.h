// The plugin's filters, written once for every MeshLab plugin API: their names, help, dialogs,
// parameter checks, what they do to a MeshDocument, what they log and how they fail. The per-API
// glue (api_2020_09/, api_2022_02/) only turns this table into its API's plugin class.
//
// The MeshLab types come from "meshlab_api.h", which each API folder provides: the same names
// (MeshDocument, RichParameterList, ...) from that version's headers, plus the few calls that
// changed between versions.
//
// Adding a filter: write its help, its parameter list and its apply function in a file of its own
// name (as overhang_analysis_filter.cpp does; filter_parts.h declares them and has what the
// filters share) and add one FilterDefinition to filter_definitions() in filters.cpp. It then
// appears in every API's build, with the parameter checks and error handling of run_filter.
#pragma once

#include <exception>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <QString>
#include <QVariant>

#include "meshlab_api.h"

namespace slim::plugin {

// Where a filter appears in MeshLab's Filters menu; each glue maps it onto its API's FilterClass
// (the names are the same in both APIs). Generic is not offered: MeshLab hides such filters.
enum class MenuCategory { Quality, Smoothing, Normal, Measure };

// Writes one line to the host's log; the glue forwards it to its API's logger.
using LogLine = std::function<void(GLLogStream::Levels level, const QString& line)>;

// What a filter's apply function gets besides the document and the parameters.
struct FilterRun {
  LogLine log;
  vcg::CallBackPos* progress = nullptr;  // may be null (scripts, tests)
  // Named results for hosts that return them (2022.02's applyFilter; pymeshlab shows them).
  std::map<std::string, QVariant> outputs;

  void info(const QString& line) const { log(GLLogStream::FILTER, line); }
  void warning(const QString& line) const { log(GLLogStream::WARNING, line); }
};

// A filter's refusal, in words for the user (what is wrong and what to change). run_filter puts
// the filter's name in front.
struct FilterFailure : std::exception {
  explicit FilterFailure(QString reason) : reason(std::move(reason)), utf8(this->reason.toStdString()) {}
  const char* what() const noexcept override { return utf8.c_str(); }
  QString reason;
  std::string utf8;
};

struct FilterDefinition {
  QString name;  // menu entry and .mlx name; must be unique across all MeshLab plugins
  // PyMeshLab's name for it (ms.apply_filter(python_name, ...)), in the style of its own filters:
  // compute_* adds attributes to the current mesh, generate_* makes a new layer. The 2022.02 glue
  // returns it as pythonFilterName; 2020.09 has no such call.
  QString python_name;
  QString info;  // HTML help shown at the top of the dialog
  MenuCategory category;
  int changed_data;  // MeshModel::MM_* the filter changes on the current layer (postCondition)
  // Adds the dialog's parameters, with defaults fitted to the mesh, to `par`.
  void (*add_parameters)(const MeshModel& m, RichParameterList& par);
  // Runs the filter on md's current layer with checked parameters. Throws FilterFailure (or any
  // exception) to refuse; it must leave the document as it was when it does.
  void (*apply)(MeshDocument& md, const RichParameterList& par, FilterRun& run);
};

// Every filter of the plugin; a filter's index here is its id in the glue (QAction ids).
const std::vector<FilterDefinition>& filter_definitions();
// The filter with that id; nullptr for an id the plugin does not have.
const FilterDefinition* find_filter(int id);
// Its name, help and PyMeshLab name; empty for an id the plugin does not have.
QString filter_name(int id);
QString filter_info(int id);
QString filter_python_name(int id);

// The glue's FilterClass for a category; `Interface` is the API's plugin interface class, whose
// FilterClass enum has these names in every version.
template <class Interface>
typename Interface::FilterClass filter_class(MenuCategory category) {
  switch (category) {
    case MenuCategory::Quality: return Interface::Quality;
    case MenuCategory::Smoothing: return Interface::Smoothing;
    case MenuCategory::Normal: return Interface::Normal;
    case MenuCategory::Measure: return Interface::Measure;
  }
  return Interface::Quality;
}

// The filter's parameters with their defaults for `m`.
RichParameterList default_parameters(const FilterDefinition& filter, const MeshModel& m);

// What is wrong with the parameters a host passed, compared with the filter's own list (missing,
// another type, an enum index out of range); empty when nothing is.
QString parameter_problem(const FilterDefinition& filter, const MeshDocument& md, const RichParameterList& par);

struct FilterOutcome {
  QString failure;  // empty on success; otherwise the reason, already written to the log
  std::map<std::string, QVariant> outputs;
  bool ok() const { return failure.isEmpty(); }
};

// Checks the parameters and runs the filter. Never throws: an exception escaping into MeshLab
// would take the user's session down. A failure's reason goes to the log as well as into the
// outcome, because meshlabserver prints only "Problem with filter" for a failed filter.
FilterOutcome run_filter(const FilterDefinition& filter, MeshDocument& md, const RichParameterList& par,
                         vcg::CallBackPos* progress, const LogLine& log);

}  // namespace slim::plugin
