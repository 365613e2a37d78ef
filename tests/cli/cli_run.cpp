#include "cli_run.h"

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <unistd.h>

namespace slim::test {
namespace fs = std::filesystem;

namespace {
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif
}  // namespace

CliRun run_cli(const std::string& args, long memory_limit_kb) {
  const fs::path err = fs::temp_directory_path() / ("slim-cli-err-" + std::to_string(::getpid()));
  std::string cmd = "'" SLIM_CLI_PATH "' " + args + " 2>'" + err.string() + "'";
  if (memory_limit_kb > 0 && !kSanitized) cmd = "ulimit -v " + std::to_string(memory_limit_kb) + "; exec " + cmd;
  CliRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  fs::remove(err);
  return r;
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("slim-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

}  // namespace slim::test
