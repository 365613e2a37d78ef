#include "filter_support_slimming.h"

#include <common/globals.h>
#include <common/mlexception.h>

#include "filters.h"

using slim::plugin::filter_definitions;
using slim::plugin::find_filter;

FilterSupportSlimming::FilterSupportSlimming() {
  for (int id = 0; id < static_cast<int>(filter_definitions().size()); ++id) {
    typeList.push_back(id);
    actionList.push_back(new QAction(filterName(id), this));  // a child of this QObject, deleted with it
  }
}

std::pair<std::string, bool> FilterSupportSlimming::getMLVersion() const {
  return {meshlab::meshlabVersion(), meshlab::builtWithDoublePrecision()};
}

QString FilterSupportSlimming::pluginName() const { return "FilterSupportSlimming"; }

QString FilterSupportSlimming::filterName(ActionIDType filter) const { return slim::plugin::filter_name(filter); }
QString FilterSupportSlimming::filterInfo(ActionIDType filter) const { return slim::plugin::filter_info(filter); }

FilterPlugin::FilterClass FilterSupportSlimming::getClass(const QAction* action) const {
  return slim::plugin::filter_class<FilterPlugin>(filter_definitions().at(ID(action)).category);
}

int FilterSupportSlimming::postCondition(const QAction* action) const {
  return filter_definitions().at(ID(action)).changed_data;
}

RichParameterList FilterSupportSlimming::initParameterList(const QAction* action, const MeshModel& m) {
  return slim::plugin::default_parameters(filter_definitions().at(ID(action)), m);
}

std::map<std::string, QVariant> FilterSupportSlimming::applyFilter(const QAction* action, const RichParameterList& par,
                                                                   MeshDocument& md, unsigned int& /*postConditionMask*/,
                                                                   vcg::CallBackPos* cb) {
  const auto* filter = find_filter(ID(action));
  if (filter == nullptr) {
    wrongActionCalled(action);  // throws MLException
    return {};
  }
  auto outcome = slim::plugin::run_filter(*filter, md, par, cb, [this](GLLogStream::Levels level, const QString& line) {
    log(level, line.toStdString());
  });
  if (!outcome.ok()) throw MLException(outcome.failure);
  return std::move(outcome.outputs);
}
