// The project's version, as CMake's project(VERSION) sets it: the one place it is written. The
// CLI prints it (--version, the JSON report), the filters put it in the log's first line, so a
// file can be traced to the build that made it.
//
//   const char* v = slim::version();   // e.g. "0.1.0"
#pragma once

namespace slim {

const char* version();

}  // namespace slim
