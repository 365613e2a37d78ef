#include "harness.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

namespace slim::test {

std::string plugin_path() { return SLIM_PLUGIN_PATH; }
std::string meshlab_prefix() { return SLIM_MESHLAB_PREFIX; }

PluginHarness::PluginHarness() : loader_(QString::fromStdString(plugin_path())) {
  QObject* instance = loader_.instance();
  plugin_ = qobject_cast<MeshFilterInterface*>(instance);
  if (plugin_) plugin_->setLog(&log_);
}

QAction* PluginHarness::action(const QString& filterName) const {
  for (QAction* a : plugin_->actions())
    if (a->text() == filterName) return a;
  return nullptr;
}

RichParameterList PluginHarness::defaults(const QString& filterName, MeshDocument& md) const {
  RichParameterList params;
  plugin_->initParameterSet(action(filterName), md, params);
  return params;
}

bool PluginHarness::apply(const QString& filterName, MeshDocument& md, const RichParameterList& params) {
  return plugin_->applyFilter(action(filterName), md, params, nullptr);
}

QStringList PluginHarness::logLines() const {
  QStringList lines;
  log_.print(lines);
  return lines;
}

ServerRun run_meshlabserver(const std::string& args) {
  namespace fs = std::filesystem;
  const fs::path home = fs::temp_directory_path() / ("slim-mlhome-" + std::to_string(::getpid()));
  fs::create_directories(home);
  // MeshLab keeps its settings under $HOME/.config/VCG: never the user's own.
  const std::string cmd = "HOME='" + home.string() + "' XDG_CONFIG_HOME='" + home.string() +
                          "/.config' '" SLIM_WITH_XVFB "' '" SLIM_MESHLAB_PREFIX "/bin/meshlabserver' " + args + " 2>&1";
  ServerRun run;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) run.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  fs::remove_all(home);
  return run;
}

}  // namespace slim::test
