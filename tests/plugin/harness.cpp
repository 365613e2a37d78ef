#include "harness.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

#include <vcg/complex/complex.h>

namespace slim::test {

PluginHarness::PluginHarness() : loader_(QString(SLIM_PLUGIN_PATH)) {
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

MeshModel* add_layer(MeshDocument& md, const Surface& s, const QString& label) {
  MeshModel* m = md.addNewMesh("", label, true);
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(m->cm, static_cast<size_t>(s.V.rows()));
  for (Eigen::Index i = 0; i < s.V.rows(); ++i, ++vi)
    vi->P() = vcg::Point3f(float(s.V(i, 0)), float(s.V(i, 1)), float(s.V(i, 2)));
  auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(m->cm, static_cast<size_t>(s.F.rows()));
  for (Eigen::Index i = 0; i < s.F.rows(); ++i, ++fi)
    for (int k = 0; k < 3; ++k) fi->V(k) = &m->cm.vert[static_cast<size_t>(s.F(i, k))];
  vcg::tri::UpdateBounding<CMeshO>::Box(m->cm);
  vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(m->cm);
  return m;
}

ServerRun run_meshlabserver(const std::string& args) {
  namespace fs = std::filesystem;
  const fs::path home = fs::temp_directory_path() / ("slim-mlhome-" + std::to_string(::getpid()));
  fs::create_directories(home);
  // MeshLab keeps its settings under $HOME/.config/VCG: never the user's own.
  const std::string cmd = "HOME='" + home.string() + "' XDG_CONFIG_HOME='" + home.string() +
                          "/.config' xvfb-run -a '" SLIM_MESHLAB_PREFIX "/bin/meshlabserver' " + args + " 2>&1";
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
