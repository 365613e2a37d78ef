// write_shape NAME OUT [LEVELS]: writes one of the test shapes (tests/support/shapes.h) as a mesh
// file, refined LEVELS times (default 0), so the evaluation tool can judge it like any mesh.
// NAME: t, mushroom, arch, window_box (a box with a 5 mm window in a side: an open mesh), or a
// creature (tests/support/creatures.h: quadruped, long_neck, upright). Exits 1 with a one-line
// reason on bad input.
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

#include "mesh_io/mesh_io.h"
#include "support/creatures.h"
#include "support/shapes.h"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::cerr << "usage: write_shape t|mushroom|arch|window_box|quadruped|long_neck|upright OUT [LEVELS]\n";
    return 1;
  }
  const std::string name = argv[1];
  const int levels = argc == 4 ? std::atoi(argv[3]) : 0;
  if (levels < 0 || levels > 4) {
    std::cerr << "write_shape: LEVELS must be 0..4\n";
    return 1;
  }
  slim::Surface s;
  const std::vector<std::string> creatures = slim::test::creature_names();
  try {
    if (name == "t") s = slim::test::t_shape();
    else if (name == "mushroom") s = slim::test::mushroom();
    else if (name == "arch") s = slim::test::arch();
    else if (name == "window_box") s = slim::test::box_with_windows(5.0);
    else if (std::find(creatures.begin(), creatures.end(), name) != creatures.end()) s = slim::test::creature(name);
    else {
      std::cerr << "write_shape: unknown shape '" << name << "' (t, mushroom, arch, window_box, quadruped, long_neck, upright)\n";
      return 1;
    }
    slim::io::save_surface(argv[2], slim::test::refined(s, levels));
  } catch (const std::exception& e) {
    std::cerr << "write_shape: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
