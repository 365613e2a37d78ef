// The plugin for MeshLab 2020.09 (MeshFilterInterface): only the API's shape. The filters
// themselves (names, dialogs, checks, what they do, log and errors) are in ../filters.h.
#pragma once

#include <QObject>

#include <common/interfaces.h>

class FilterSupportSlimming : public QObject, public MeshFilterInterface {
  Q_OBJECT
  // FILE makes plugin.json (the top-level plugin.json, versions filled in by CMake) the plugin's metadata: name,
  // version, MeshLab version, licence. MeshLab 2020.09's MESHLAB_PLUGIN_IID_EXPORTER cannot pass it.
  Q_PLUGIN_METADATA(IID MESH_FILTER_INTERFACE_IID FILE "plugin.json")
  Q_INTERFACES(MeshFilterInterface)

 public:
  FilterSupportSlimming();

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* action) override;
  FILTER_ARITY filterArity(QAction*) const override { return SINGLE_MESH; }
  int getPreConditions(QAction*) const override { return MeshModel::MM_NONE; }
  int postCondition(QAction* action) const override;
  void initParameterSet(QAction* action, MeshModel& m, RichParameterList& par) override;
  // False with the reason in errorMessage and in the log (meshlabserver shows only the log).
  bool applyFilter(QAction* action, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb) override;
};
