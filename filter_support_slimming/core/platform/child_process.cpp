#include "core/platform/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace slim {

namespace {

// The address space this process maps now (VmSize), in bytes; 0 if unknown. The child starts as
// a copy of it, and a GUI host can map gigabytes it never touches, so the child's limit is this
// plus what it may add.
double mapped_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) return 1024.0 * std::atof(line.c_str() + 7);
  return 0.0;
}

// address_limit: RLIMIT_AS for the child in bytes, 0 = none (computed before the fork).
[[noreturn]] void child_main(int fd, const std::function<bool(int)>& body, double address_limit) {
  struct sigaction dfl;
  std::memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(sig, &dfl, nullptr);
  if (address_limit > 0) {
    struct rlimit limit;
    limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(address_limit);
    setrlimit(RLIMIT_AS, &limit);
  }
  const int devnull = ::open("/dev/null", O_WRONLY);
  if (devnull >= 0) dup2(devnull, STDOUT_FILENO);  // the library's chatter stays out of the host's log
  _exit(body(fd) ? 0 : 3);
}

double now_seconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string signal_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV, a segmentation fault";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT, an abort";
    case SIGKILL: return "SIGKILL, probably the out-of-memory killer";
    default: return "signal " + std::to_string(sig);
  }
}

std::string capitalised(std::string text) {
  if (!text.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}

// Reads the pipe until the child closes it or the deadline passes; true when it timed out.
bool read_until_closed(int fd, double deadline, std::vector<char>& data) {
  char buffer[1 << 16];
  for (;;) {
    const double left = deadline - now_seconds();
    if (left <= 0) return true;
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(std::min(left * 1000.0 + 1.0, 1000.0)));
    if (ready < 0 && errno != EINTR) return false;
    if (ready <= 0) continue;
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data.insert(data.end(), buffer, buffer + n);
  }
}

// How the child ended, as an error, or nothing when it exited with status 0 (or was reaped by the
// host itself: the result then speaks for itself, since a crashed child cannot have written a
// complete one).
void check_exit(pid_t pid, pid_t reaped, int status, const ChildProcessOptions& o, double address_limit) {
  if (reaped != pid) return;
  if (WIFSIGNALED(status))
    throw std::runtime_error(o.name + " crashed (" + signal_name(WTERMSIG(status)) +
                             ") on this mesh; its process was separate, so nothing else was lost. " +
                             capitalised(o.advice));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    // An allocator that dies at the address-space limit instead of throwing (AddressSanitizer's,
    // a C library's) ends the child this way: say that it may have been memory.
    std::ostringstream msg;
    msg << o.name << "'s process ended abnormally (exit status " << WEXITSTATUS(status) << ")";
    if (address_limit > 0)
      msg << "; it may have run out of memory (limited to " << o.memory_bytes / 1e9
          << " GB more than this process maps); " << o.advice;
    throw std::runtime_error(msg.str());
  }
}

}  // namespace

bool write_all(int fd, const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    bytes -= static_cast<size_t>(n);
  }
  return true;
}

std::vector<char> run_in_child(const std::function<bool(int fd)>& body, const ChildProcessOptions& o) {
  const double address_limit = o.memory_bytes > 0 ? mapped_bytes() + o.memory_bytes : 0.0;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error("could not create a pipe for " + o.name + ": " + std::string(std::strerror(errno)));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("could not start a process for " + o.name + ": " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {
    close(fds[0]);
    child_main(fds[1], body, address_limit);
  }
  close(fds[1]);
  std::vector<char> data;
  const double deadline = now_seconds() + o.timeout_seconds;
  bool timed_out = read_until_closed(fds[0], deadline, data);
  close(fds[0]);
  // The child closes the pipe only by exiting; give it until the deadline to be reaped.
  int status = 0;
  pid_t reaped = 0;
  while (!timed_out) {
    reaped = waitpid(pid, &status, WNOHANG);
    if (reaped == pid || (reaped < 0 && errno != EINTR)) break;
    if (now_seconds() > deadline) timed_out = true;
    else usleep(1000);
  }
  if (timed_out) {
    kill(pid, SIGKILL);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    std::ostringstream msg;
    msg << o.name << " did not finish within " << o.timeout_seconds << " s and was stopped; " << o.advice
        << " or a larger timeout";
    throw std::runtime_error(msg.str());
  }
  check_exit(pid, reaped, status, o, address_limit);
  return data;
}

}  // namespace slim
