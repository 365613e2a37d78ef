// Runs a piece of work in a forked child process and returns the bytes it wrote: how the TetGen
// domain (tetgen_domain.h) keeps a library that can crash, hang or exhaust memory away from the
// host (inside MeshLab a crash would lose the user's unsaved work).
//
//   std::vector<char> out = run_in_child(body, options);
//
// Inputs
//   body     runs in the child: writes its result to the pipe `fd` (write_all) and returns true
//            when all of it was written. As befits a fork of a multi-threaded process it should
//            only compute, write() and return: the child then _exit()s at once.
//   options  the work's name and what to advise, for the messages; the timeout; the address space
//            the child may map beyond what the host maps now.
// Output: everything the child wrote, once it has exited with status 0.
// Errors: std::runtime_error, naming the work, when the pipe or the fork fails, the child crashes
// (a signal), times out (it is then killed), or exits otherwise; the host lives on. Before the
// body runs, the child restores the default action of the fatal signals (the host's crash
// handlers belong to the host), sets RLIMIT_AS, and sends its stdout to /dev/null.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace slim {

struct ChildProcessOptions {
  std::string name = "the child process";  // "TetGen": "TetGen crashed (...)"
  std::string advice;                       // appended to failures, e.g. "use the voxel domain"
  double timeout_seconds = 60.0;
  double memory_bytes = 0.0;                // extra address space for the child; 0 = no limit
};

std::vector<char> run_in_child(const std::function<bool(int fd)>& body, const ChildProcessOptions& options);

// write() until all bytes are out; false on an error.
bool write_all(int fd, const void* data, size_t bytes);

}  // namespace slim
