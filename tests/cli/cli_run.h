// Runs the support-slim CLI as a user does, for the CLI tests.
#pragma once

#include <filesystem>
#include <string>

namespace slim::test {

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

// `args` after the binary's path, through /bin/sh (quote paths). With `memory_limit_kb` > 0, the
// run's address space is limited to that (ulimit -v), except in sanitized builds, whose shadow
// memory needs terabytes of address space.
CliRun run_cli(const std::string& args, long memory_limit_kb = 0);

// A fresh scratch folder for this test process.
std::filesystem::path scratch();

}  // namespace slim::test
