// Where the tests find the checkout's own files.
// Out: absolute paths without a trailing slash.
// Why functions, not macros: the paths are compiled into source_paths.cpp alone, so every other
// test object is the same in any checkout, and ccache can reuse it from one clone to the next.
#pragma once

#include <string>

namespace slim::test {

std::string source_dir();  // the checkout's root (examples/, scripts/, tests/fuzz/, eval/)
std::string data_dir();    // the sample data (bunny.ply), set up by scripts/setup.sh

}  // namespace slim::test
