// Runs a shell command and captures what it prints, for the tests that drive whole programs.
#pragma once

#include <string>

namespace slim::test {

struct CommandRun {
  int exit_code = -1;  // -1 when the command could not start or did not exit normally
  std::string output;  // stdout and stderr together
};

CommandRun run_command(const std::string& command);

// Quotes a string for the shell (single quotes).
std::string shell_quote(const std::string& s);

}  // namespace slim::test
