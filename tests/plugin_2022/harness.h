// In-process MeshLab 2022.02 harness: loads the built plugin with QPluginLoader (absolute path)
// and runs its filters on a MeshDocument the way MeshLab 2022.02 does (initParameterList, then
// applyFilter, which throws MLException when a filter fails).
#pragma once

#include <map>
#include <string>

#include <QJsonObject>
#include <QPluginLoader>
#include <QString>
#include <QStringList>
#include <QVariant>

#include <common/GLLogStream.h>
#include <common/ml_document/mesh_document.h>
#include <common/plugins/interfaces/filter_plugin.h>

#include "layers.h"

namespace slim::test {

class PluginHarness {
 public:
  PluginHarness();  // loads SLIM_PLUGIN_PATH; failures surface through ok()/error()
  bool ok() const { return plugin_ != nullptr; }
  QString error() const { return loader_.errorString(); }
  FilterPlugin* plugin() const { return plugin_; }
  QJsonObject metaData() const { return loader_.metaData().value("MetaData").toObject(); }

  QAction* action(const QString& filterName) const;  // nullptr when the plugin has no such filter
  // The filter's parameters with their defaults for the current mesh of md.
  RichParameterList defaults(const QString& filterName, const MeshDocument& md) const;
  // Runs the filter. True with its named results in outputs(); false when it threw MLException,
  // with the exception's text in lastError(). Other exceptions propagate: MeshLab 2022.02 would
  // not catch them either. The log lines it wrote are appended to logLines().
  bool apply(const QString& filterName, MeshDocument& md, const RichParameterList& params,
             vcg::CallBackPos* progress = nullptr);
  const std::map<std::string, QVariant>& outputs() const { return outputs_; }
  QString lastError() const { return last_error_; }
  QStringList logLines() const;

 private:
  QPluginLoader loader_;
  FilterPlugin* plugin_ = nullptr;
  GLLogStream log_;
  std::map<std::string, QVariant> outputs_;
  QString last_error_;
};

}  // namespace slim::test
