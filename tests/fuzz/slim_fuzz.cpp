// The libFuzzer target: fuzz bytes -> a mesh and settings (fuzz_case.h) -> the core, every outcome
// checked. A result that is not sane aborts, so libFuzzer keeps the input as a crash. Build with
// -DSLIM_FUZZ=ON and clang; scripts/fuzz.sh runs it (docs/robustness.md: Fuzzing).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz/fuzz_case.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const std::string problem = slim::fuzz::run_fuzz_case(slim::fuzz::decode(data, size));
  if (!problem.empty()) {
    std::fprintf(stderr, "slim_fuzz: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
