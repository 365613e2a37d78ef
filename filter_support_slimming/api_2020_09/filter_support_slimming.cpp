#include "filter_support_slimming.h"

#include "filters.h"

using slim::plugin::filter_definitions;
using slim::plugin::find_filter;

FilterSupportSlimming::FilterSupportSlimming() {
  for (int id = 0; id < static_cast<int>(filter_definitions().size()); ++id) {
    typeList << id;
    actionList << new QAction(filterName(id), this);  // a child of this QObject, deleted with it
  }
}

QString FilterSupportSlimming::pluginName() const { return "FilterSupportSlimming"; }

QString FilterSupportSlimming::filterName(FilterIDType filter) const { return slim::plugin::filter_name(filter); }
QString FilterSupportSlimming::filterInfo(FilterIDType filter) const { return slim::plugin::filter_info(filter); }

MeshFilterInterface::FilterClass FilterSupportSlimming::getClass(QAction* action) {
  return slim::plugin::filter_class<MeshFilterInterface>(filter_definitions().at(ID(action)).category);
}

int FilterSupportSlimming::postCondition(QAction* action) const {
  return filter_definitions().at(ID(action)).changed_data;
}

void FilterSupportSlimming::initParameterSet(QAction* action, MeshModel& m, RichParameterList& par) {
  par.join(slim::plugin::default_parameters(filter_definitions().at(ID(action)), m));
}

bool FilterSupportSlimming::applyFilter(QAction* action, MeshDocument& md, const RichParameterList& par,
                                        vcg::CallBackPos* cb) {
  const auto* filter = find_filter(ID(action));
  if (filter == nullptr) {
    errorMessage = "Unknown filter";
    return false;
  }
  const auto outcome = slim::plugin::run_filter(*filter, md, par, cb, [this](GLLogStream::Levels level, const QString& line) {
    Log(level, "%s", qUtf8Printable(line));
  });
  errorMessage = outcome.failure;
  return outcome.ok();
}
