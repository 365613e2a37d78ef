// The version the checkout's CMakeLists.txt declares (project(... VERSION x.y.z)), read from the
// file itself: what every output's version must match.
#pragma once

#include <string>

namespace slim::test {

std::string project_version();  // "" when the file has no such line

}  // namespace slim::test
