#include "key_values.h"

#include <fstream>
#include <sstream>

namespace slim::test {

std::map<std::string, double> parse_key_values(const std::string& text) {
  std::map<std::string, double> m;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    try {
      m[line.substr(0, eq)] = std::stod(line.substr(eq + 1));
    } catch (const std::exception&) {  // not a number
    }
  }
  return m;
}

std::map<std::string, double> read_key_values(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return parse_key_values(s.str());
}

std::filesystem::path scratch_dir(const std::filesystem::path& root, const std::string& name) {
  const std::filesystem::path dir = root / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace slim::test
