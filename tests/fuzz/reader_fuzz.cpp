// The libFuzzer target for the CLI's mesh readers: fuzz bytes -> a PLY, STL, OBJ or OFF file
// (reader_case.h) -> vcg_adapters/mesh_io, every outcome checked. An outcome that is not sane
// aborts, so libFuzzer keeps the input as a crash. Build with -DSLIM_FUZZ=ON and clang;
// scripts/fuzz.sh runs it beside slim_fuzz (docs/robustness.md).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz/reader_case.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const std::string problem = slim::fuzz::run_reader_case(data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "reader_fuzz: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
