#include "core/platform/version.h"

namespace slim {

// SLIM_VERSION is defined for this file alone (core/CMakeLists.txt), so a new version recompiles
// one file.
const char* version() { return SLIM_VERSION; }

}  // namespace slim
