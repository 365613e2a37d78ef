// The MeshLab 2020.09 plugin: parameters, layers, log and errors. No geometry lives here; the
// filters convert the layer with vcg_adapters/, call the core and write the results back.
#pragma once

#include <QObject>

#include <common/interfaces.h>

class FilterSupportSlimming : public QObject, public MeshFilterInterface {
  Q_OBJECT
  // FILE makes plugin.json the plugin's metadata (name, version, MeshLab version, licence);
  // MeshLab 2020.09's MESHLAB_PLUGIN_IID_EXPORTER cannot pass it.
  Q_PLUGIN_METADATA(IID MESH_FILTER_INTERFACE_IID FILE "../plugin.json")
  Q_INTERFACES(MeshFilterInterface)

 public:
  enum { FP_OVERHANG_ANALYSIS, FP_SUPPORT_SLIMMING };

  FilterSupportSlimming();
  ~FilterSupportSlimming() override;

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* action) override;
  FILTER_ARITY filterArity(QAction* action) const override;
  int getPreConditions(QAction* action) const override;
  int postCondition(QAction* action) const override;
  void initParameterSet(QAction* action, MeshModel& m, RichParameterList& parlst) override;
  bool applyFilter(QAction* action, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb) override;

 private:
  bool applyOverhangAnalysis(MeshDocument& md, const RichParameterList& par);
  bool applySupportSlimming(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb);
  // What is wrong with the parameters a host passed, compared with initParameterSet's (missing,
  // another type, an enum index out of range); empty when nothing is.
  QString parameterProblem(QAction* action, MeshDocument& md, const RichParameterList& par);
  // Puts the reason in the filter's error message and in the log, then returns false: with only
  // errorMessage, meshlabserver prints nothing but "Problem with filter".
  bool fail(const QString& reason);
};
