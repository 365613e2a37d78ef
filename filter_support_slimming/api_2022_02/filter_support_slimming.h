// The plugin for MeshLab 2022.02 and later (FilterPlugin): only the API's shape. The filters
// themselves (names, dialogs, checks, what they do, log and errors) are in ../filters.h.
#pragma once

#include <QObject>

#include <common/plugins/interfaces/filter_plugin.h>

class FilterSupportSlimming : public QObject, public FilterPlugin {
  Q_OBJECT
  // MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID) would give the plugin no metadata. FILE makes
  // plugin.json (the top-level plugin.json, versions filled in by CMake) its metadata, as in the 2020.09 build,
  // and getMLVersion() below is the rest of what that macro defines.
  Q_PLUGIN_METADATA(IID FILTER_PLUGIN_IID FILE "plugin.json")
  Q_INTERFACES(FilterPlugin)

 public:
  FilterSupportSlimming();

  // The MeshLab version and precision this plugin was compiled for (MESHLAB_VERSION and
  // MESHLAB_SCALAR); MeshLab refuses to load a plugin whose values differ from its own.
  std::pair<std::string, bool> getMLVersion() const override;
  QString pluginName() const override;
  QString filterName(ActionIDType filter) const override;
  QString filterInfo(ActionIDType filter) const override;
  QString pythonFilterName(ActionIDType filter) const override;  // PyMeshLab's name
  FilterClass getClass(const QAction* action) const override;
  FilterArity filterArity(const QAction*) const override { return SINGLE_MESH; }
  int getPreConditions(const QAction*) const override { return MeshModel::MM_NONE; }
  int postCondition(const QAction* action) const override;
  RichParameterList initParameterList(const QAction* action, const MeshModel& m) override;
  // Throws MLException with the reason (also written to the log) when the filter fails; returns
  // the filter's named results (risky area, ...) otherwise.
  std::map<std::string, QVariant> applyFilter(const QAction* action, const RichParameterList& par, MeshDocument& md,
                                              unsigned int& postConditionMask, vcg::CallBackPos* cb) override;
};
