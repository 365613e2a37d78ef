#include "harness.h"

#include <common/mlexception.h>

namespace slim::test {

PluginHarness::PluginHarness() : loader_(QString(SLIM_PLUGIN_PATH)) {
  plugin_ = qobject_cast<FilterPlugin*>(loader_.instance());
  if (plugin_) plugin_->setLog(&log_);
}

QAction* PluginHarness::action(const QString& filterName) const {
  for (QAction* a : plugin_->actions())
    if (a->text() == filterName) return a;
  return nullptr;
}

RichParameterList PluginHarness::defaults(const QString& filterName, const MeshDocument& md) const {
  return plugin_->initParameterList(action(filterName), md);
}

bool PluginHarness::apply(const QString& filterName, MeshDocument& md, const RichParameterList& params,
                          vcg::CallBackPos* progress) {
  outputs_.clear();
  last_error_.clear();
  const QAction* a = action(filterName);
  unsigned int postConditionMask = plugin_->postCondition(a);  // what MeshLab passes in
  try {
    outputs_ = plugin_->applyFilter(a, params, md, postConditionMask, progress);
    return true;
  } catch (const MLException& e) {
    last_error_ = QString::fromLocal8Bit(e.what());
    return false;
  }
}

QStringList PluginHarness::logLines() const {
  QStringList lines;
  log_.print(lines);
  return lines;
}

}  // namespace slim::test
