#include "support/project_version.h"

#include <fstream>
#include <regex>
#include <sstream>

#include "support/source_paths.h"

namespace slim::test {

std::string project_version() {
  std::ifstream in(source_dir() + "/CMakeLists.txt");
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::smatch m;
  if (!std::regex_search(s, m, std::regex(R"(project\(support_slimming VERSION ([0-9.]+))"))) return "";
  return m[1];
}

}  // namespace slim::test
