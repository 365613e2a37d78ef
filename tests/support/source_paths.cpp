#include "support/source_paths.h"

namespace slim::test {

std::string source_dir() { return SLIM_SOURCE_DIR; }
std::string data_dir() { return SLIM_DATA_DIR; }

}  // namespace slim::test
