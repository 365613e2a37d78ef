// In-process MeshLab harness: loads the built plugin with QPluginLoader (absolute path) and runs
// its filters on a MeshDocument the way MeshLab does, plus helpers to run the real meshlabserver.
#pragma once

#include <memory>
#include <string>

#include <QPluginLoader>
#include <QString>
#include <QStringList>

#include <common/GLLogStream.h>
#include <common/interfaces.h>
#include <common/meshmodel.h>

#include "core/geometry/surface.h"
#include "layers.h"

namespace slim::test {

class PluginHarness {
 public:
  PluginHarness();  // loads plugin_path(); ASSERT-style failures surface through ok()/error()
  bool ok() const { return plugin_ != nullptr; }
  QString error() const { return loader_.errorString(); }
  MeshFilterInterface* plugin() const { return plugin_; }
  QJsonObject metaData() const { return loader_.metaData(); }

  QAction* action(const QString& filterName) const;  // nullptr when the plugin has no such filter
  // The filter's parameters with their defaults for the current mesh of md.
  RichParameterList defaults(const QString& filterName, MeshDocument& md) const;
  // Runs the filter; the log lines it wrote are appended to log().
  bool apply(const QString& filterName, MeshDocument& md, const RichParameterList& params);
  QStringList logLines() const;
  QString lastError() const { return plugin_->errorMsg(); }

 private:
  QPluginLoader loader_;
  MeshFilterInterface* plugin_ = nullptr;
  GLLogStream log_;
};

// Result of a meshlabserver run.
struct ServerRun {
  int exit_code = -1;
  std::string output;  // stdout + stderr
};
// The built plugin (absolute path), and the private MeshLab prefix whose meshlabserver the tests run.
// Functions, not macros, for the reason support/source_paths.h gives.
std::string plugin_path();
std::string meshlab_prefix();

// Runs PREFIX/bin/meshlabserver under xvfb-run with a throwaway HOME; `args` are appended.
ServerRun run_meshlabserver(const std::string& args);

}  // namespace slim::test
