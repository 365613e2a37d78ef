// The risky-area reduction against the deviation budget, for both methods, on the sample bunny and
// the synthetic overhang shapes: the table in the closing note of the slimming work.
//   slimming_curve [--angle DEG] [--resolution N] [--budgets 1,2,3,5,10] [--iterations N] [--shape NAME]
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/optimizer/slimming.h"
#include "support/shapes.h"

using namespace slim;

int main(int argc, char** argv) {
  SlimmingOptions base;
  base.steps.max_iterations = 200;
  std::vector<double> budgets{1, 2, 3, 5, 10};
  std::string only;  // --shape NAME: that shape alone
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--angle") base.print.alpha_max_deg = std::stod(v);
    else if (a == "--resolution") base.resolution = std::stoi(v);
    else if (a == "--iterations") base.steps.max_iterations = std::stoi(v);
    else if (a == "--stall") base.steps.stall_tolerance = std::stod(v);
    else if (a == "--step") base.steps.max_step_deg = std::stod(v);
    else if (a == "--shape") only = v;
    else if (a == "--budgets") {
      budgets.clear();
      std::stringstream ss(v);
      std::string part;
      while (std::getline(ss, part, ',')) budgets.push_back(std::stod(part));
    }
  }
  const std::vector<std::pair<std::string, Surface>> shapes{
      {"bunny", test::load_mesh(test::sample_bunny_path())},
      {"T", test::refined(test::t_shape(), 4)},
      {"mushroom", test::refined(test::mushroom(), 2)},
      {"arch", test::refined(test::arch(), 3)}};
  std::printf("alpha_max %.0f deg, resolution %d; cells: risky-area reduction %%, shadow-volume reduction %% "
              "(iterations, inverted tets)\n",
              base.print.alpha_max_deg, base.resolution);
  std::printf("%-9s %-9s", "shape", "method");
  for (double b : budgets) std::printf(" | %5.1f%% budget             ", b);
  std::printf("\n");
  for (const auto& [name, mesh] : shapes) {
    if (!only.empty() && name != only) continue;
    for (SlimmingMethod method : {SlimmingMethod::Paper, SlimmingMethod::Coherent}) {
      std::printf("%-9s %-9s", name.c_str(), method == SlimmingMethod::Paper ? "paper" : "coherent");
      for (double b : budgets) {
        SlimmingOptions o = base;
        o.method = method;
        o.budget = DeviationBudget::from_percent(b);
        const SlimmingResult r = slim_supports(mesh, o);
        const double cut = r.before.risky_area > 0 ? 100.0 * (1.0 - r.after.risky_area / r.before.risky_area) : 0.0;
        const double shadow_cut =
            r.before.shadow_volume > 0 ? 100.0 * (1.0 - r.after.shadow_volume / r.before.shadow_volume) : 0.0;
        std::printf(" | %6.1f %6.1f (%3d it, %2d inv)", cut, shadow_cut, r.iterations, r.history.back().inverted_tets);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  return 0;
}
