#include "filters.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/platform/version.h"
#include "filter_parts.h"

namespace slim::plugin {

// ---- the table -------------------------------------------------------------------------------

const std::vector<FilterDefinition>& filter_definitions() {
  static const std::vector<FilterDefinition> filters = {
      {"Overhang Analysis", "compute_scalar_by_overhang_per_face", kOverhangAnalysisInfo, MenuCategory::Quality,
       MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR | MeshModel::MM_FACEFLAGSELECT,
       add_overhang_analysis_parameters, apply_overhang_analysis},
      {"Support Slimming", "generate_support_slimmed_mesh", kSupportSlimmingInfo, MenuCategory::Smoothing,
       MeshModel::MM_NONE,  // the result is a new layer; the input layer is left as it was
       add_support_slimming_parameters, apply_support_slimming},
      {"Print Orientation", "generate_print_oriented_mesh", kPrintOrientationInfo, MenuCategory::Normal,
       MeshModel::MM_NONE,  // the result is a new layer; the input layer is left as it was
       add_print_orientation_parameters, apply_print_orientation},
  };
  return filters;
}

const FilterDefinition* find_filter(int id) {
  const auto& filters = filter_definitions();
  return id >= 0 && id < static_cast<int>(filters.size()) ? &filters[static_cast<size_t>(id)] : nullptr;
}

QString filter_name(int id) {
  const FilterDefinition* f = find_filter(id);
  return f ? f->name : QString();
}

QString filter_info(int id) {
  const FilterDefinition* f = find_filter(id);
  return f ? f->info : QString();
}

QString filter_python_name(int id) {
  const FilterDefinition* f = find_filter(id);
  return f ? f->python_name : QString();
}

// ---- what every filter shares ----------------------------------------------------------------

RichParameterList default_parameters(const FilterDefinition& filter, const MeshModel& m) {
  RichParameterList par;
  filter.add_parameters(m, par);
  return par;
}

QString parameter_problem(const FilterDefinition& filter, const MeshDocument& md, const RichParameterList& par) {
  // A hand-written .mlx can drop a parameter, give it another type or an enum index out of range.
  // MeshLab's typed getters assert (abort the host) on a wrong type and throw on a missing name,
  // so everything is compared with our own list before any value is read.
  if (md.mm() == nullptr) return {};
  const RichParameterList expected = default_parameters(filter, *md.mm());
  for (const RichParameter& want : expected) {
    if (!par.hasParameter(want.name()))
      return QString("the parameter '%1' (%2) is missing; a script must list every parameter of the filter")
          .arg(want.name(), want.fieldDescription());
    const RichParameter& got = par.getParameterByName(want.name());
    if (!meshlab_api::same_parameter_type(got, want))
      return QString("the parameter '%1' (%2) is a %3, but it must be a %4")
          .arg(want.name(), want.fieldDescription(), got.stringType(), want.stringType());
    if (const auto* wantEnum = dynamic_cast<const RichEnum*>(&want)) {
      const int count = wantEnum->enumvalues.size();
      const int index = meshlab_api::enum_index(got);
      if (index < 0 || index >= count)
        return QString("the parameter '%1' (%2) is %3, but it must be one of 0..%4 (%5)")
            .arg(want.name(), want.fieldDescription())
            .arg(index)
            .arg(count - 1)
            .arg(wantEnum->enumvalues.join(", "));
    }
  }
  return {};
}

FilterOutcome run_filter(const FilterDefinition& filter, MeshDocument& md, const RichParameterList& par,
                         vcg::CallBackPos* progress, const LogLine& log) {
  FilterOutcome outcome;
  const auto fail = [&](const QString& reason) {
    outcome.failure = filter.name + ": " + reason;
    log(GLLogStream::WARNING, outcome.failure);
  };
  try {
    const QString problem = parameter_problem(filter, md, par);
    if (!problem.isEmpty()) {
      fail(problem);
      return outcome;
    }
    FilterRun run{log, progress, {}};
    run.info(filter.name + ": support-slimming " + slim::version());  // which build made the result
    filter.apply(md, par, run);
    outcome.outputs = std::move(run.outputs);
    // The version in the outputs too, as numbers: PyMeshLab hands back numbers only.
    const QStringList parts = QString(slim::version()).split('.');
    const char* keys[] = {"version_major", "version_minor", "version_patch"};
    for (int k = 0; k < 3 && k < parts.size(); ++k) outcome.outputs[keys[k]] = parts[k].toInt();
  } catch (const FilterFailure& e) {
    fail(e.reason);
  } catch (const slim::Cancelled&) {
    fail("cancelled; the document is unchanged");
  } catch (const std::exception& e) {
    fail(QString::fromUtf8(e.what()));
  } catch (...) {
    fail("unexpected internal error");
  }
  return outcome;
}

}  // namespace slim::plugin
