// The real MeshLab GUI (the private prefix's copy, so it loads this build's plugin), driven under
// Xvfb with xdotool by gui_check.sh: Filters -> Smoothing, Fairing and Deformation -> Support
// Slimming -> Apply must leave a new "<name>_slimmed" layer whose mesh is the deformed input, and
// the dialog must show every parameter on the 1280x1024 screen, with and without the help lines
// (the last one, found by ticking it, whole and inside the dialog: gui_check.sh's
// check_last_parameter). The least saving, the crease limit and the budget's percentage field
// are typed into the dialog, and the filter's log must give those values back (the budget in mm).
// Label gui; exclude it with ctest -LE gui.
#include <gtest/gtest.h>

#include <QApplication>
#include <QDir>

#include <cstdio>
#include <filesystem>

#include <common/pluginmanager.h>

#include "core/print/overhang.h"
#include "harness.h"
#include "mesh_io/mesh_io.h"
#include "run_command.h"
#include "support/shapes.h"
#include "support/source_paths.h"

using namespace slim;
namespace fs = std::filesystem;

namespace {

// The filter's place in Filters -> Smoothing, Fairing and Deformation, found the way MeshLab
// builds that menu: every filter of every plugin in the prefix, by name (MeshLab's own
// PluginManager loads them), the Smoothing-class ones in that order. -1 when absent.
int smoothing_menu_index(const QString& filter) {
  PluginManager pm;
  RichParameterList globals;
  pm.loadPlugins(globals, QDir(QString::fromStdString(test::meshlab_prefix() + "/lib/x86_64-linux-gnu/meshlab/plugins")));
  int index = 0;
  for (auto it = pm.stringFilterMap.begin(); it != pm.stringFilterMap.end(); ++it) {
    QAction* action = it.value()->AC(it.key());
    if (!(it.value()->getClass(action) & MeshFilterInterface::Smoothing)) continue;
    if (it.key() == filter) return index;
    ++index;
  }
  return -1;
}

}  // namespace

TEST(MeshLabGui, SupportSlimmingFromTheFiltersMenuAddsASlimmedLayer) {
  const std::string mesh = test::sample_bunny_path();
  ASSERT_TRUE(fs::exists(mesh)) << "run scripts/setup.sh first";
  const int index = smoothing_menu_index("Support Slimming");
  ASSERT_GE(index, 0) << "the prefix's plugins offer no Smoothing-class 'Support Slimming' filter";

  // Kept after the test: the screenshots are its record.
  const fs::path out = fs::path(SLIM_GUI_OUT_DIR);
  const test::CommandRun r =
      test::run_command("timeout 300 " + test::shell_quote(test::source_dir() + "/tests/eval/gui_check.sh") + " " +
                        test::shell_quote(test::meshlab_prefix()) + " " + test::shell_quote(mesh) + " " +
                        test::shell_quote(out.string()) + " " + std::to_string(index));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string layer_name = fs::path(mesh).stem().string() + "_slimmed";  // "bunny.ply" -> "bunny_slimmed"
  EXPECT_NE(r.output.find("export dialog: Save \"" + layer_name + "\" Layer"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("last parameter visible: yes"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("help fits: yes"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("displacement colours shown: yes"), std::string::npos) << r.output;
  // The values typed: 0 into Least saving, 2.5 into Crease limit, 4 into the budget's % field.
  EXPECT_NE(r.output.find("Support Slimming: crease limit 2.5% of the edge length, least saving 0%"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("mm (4% of the bbox diagonal)"), std::string::npos) << r.output;
  for (const char* line : {"dialog geometry: ", "last parameter's check mark: ", "dialog with help: ", "ramp-blue pixels: "}) {
    const size_t from = r.output.find(line);
    if (from != std::string::npos) std::printf("%s\n", r.output.substr(from, r.output.find('\n', from) - from).c_str());
  }
  // The dialog fits on the screen: its window ends above the screen's bottom edge (1024 pixels).
  const size_t at = r.output.find("dialog geometry: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  int w = 0, h = 0, x = 0, y = 0;
  ASSERT_EQ(std::sscanf(r.output.c_str() + at, "dialog geometry: %dx%d+%d+%d", &w, &h, &x, &y), 4) << r.output;
  EXPECT_LE(y + h, 1024) << r.output;
  EXPECT_GT(fs::file_size(out / "dialog.png"), 10000u);
  EXPECT_GT(fs::file_size(out / "meshlab_gui.png"), 10000u);

  // The exported layer is the input deformed: same mesh, vertices moved, fewer risky faces.
  const Surface input = test::load_mesh(mesh);
  io::FaceExtras extras;
  const Surface layer = io::load_surface((out / "layer.ply").string(), &extras);
  ASSERT_EQ(layer.V.rows(), input.V.rows());
  ASSERT_EQ(layer.F, input.F);
  const double diag = (input.V.colwise().maxCoeff() - input.V.colwise().minCoeff()).norm();
  const double moved = (layer.V - input.V).rowwise().norm().maxCoeff();
  EXPECT_GT(moved, 1e-3 * diag);
  EXPECT_LE(moved, 0.04 * diag * 1.001);  // the deviation budget typed: 4%
  ASSERT_EQ(extras.quality.size(), layer.F.rows()) << "the layer carries the filter's face quality";
  PrintSetup o;
  o.plate = PlateRule::within(1e-3 * diag);  // the dialog's default: 0.1% of the diagonal
  EXPECT_LT(analyse_overhang(layer, o).risky_area, 0.95 * analyse_overhang(input, o).risky_area);
}

int main(int argc, char** argv) {
  qputenv("QT_QPA_PLATFORM", "offscreen");  // this process only lists plugins; the GUI runs under Xvfb
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
