// support-slim IN... --out-dir DIR as a user runs it: five files of four formats with one bad; the
// batch goes on past the bad one, writes what a run of each file alone writes, prints one table
// and one JSON line per file, and exits 1 because one failed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "mesh_io/mesh_io.h"
#include "support/shapes.h"

using namespace slim;
namespace fs = std::filesystem;
using test::CliRun;
using test::run_cli;

namespace {

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string shell_path(const fs::path& p) { return "'" + p.string() + "'"; }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

}  // namespace

TEST(CliBatch, FiveFilesOneBadGoOnAndAgreeWithSingleRuns) {
  const fs::path dir = test::scratch(), out = dir / "out", single = dir / "single";
  fs::create_directories(out);
  fs::create_directories(single);
  fs::copy_file(test::sample_bunny_path(), dir / "bunny.ply");
  io::save_surface((dir / "t.stl").string(), test::t_shape());
  io::save_surface((dir / "arch.obj").string(), test::refined(test::arch(), 1));
  io::save_surface((dir / "arch.3mf").string(), test::refined(test::arch(), 0));
  std::ofstream(dir / "bad.off") << "OFF\n-5 4 0\n";
  const std::vector<std::string> inputs = {"bunny.ply", "t.stl", "arch.obj", "bad.off", "arch.3mf"};
  std::string args;
  for (const std::string& in : inputs) args += shell_path(dir / in) + " ";
  const CliRun batch = run_cli(args + "--out-dir " + shell_path(out) + " --report " + shell_path(dir / "r.jsonl") + " --quiet");
  EXPECT_EQ(batch.exit_code, 1) << batch.out << batch.err;  // one failed
  EXPECT_NE(batch.err.find("support-slim: cannot read " + (dir / "bad.off").string()), std::string::npos) << batch.err;

  for (const std::string& in : inputs) {
    const fs::path p(in), written = out / (p.stem().string() + "_slimmed" + p.extension().string());
    if (in == "bad.off") {
      EXPECT_FALSE(fs::exists(written));
      continue;
    }
    const CliRun alone = run_cli(shell_path(dir / in) + " -o " + shell_path(single / written.filename()) + " --quiet");
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    if (p.extension() == ".3mf") {  // lib3mf gives each object a fresh UUID: compare what it holds
      const io::MeshFile a = io::read_mesh(written.string()), b = io::read_mesh((single / written.filename()).string());
      EXPECT_TRUE(a.surface.V == b.surface.V && a.surface.F == b.surface.F) << in;
    } else {
      EXPECT_TRUE(bytes_of(written) == bytes_of(single / written.filename())) << in;  // the same run, the same file
    }
    EXPECT_NE(batch.out.find(in + " "), std::string::npos) << in << "\n" << batch.out;
  }
  const std::vector<std::string> table = lines_of(batch.out);
  EXPECT_NE(batch.out.find("4 of 5 files done, 1 failed"), std::string::npos) << batch.out;
  EXPECT_TRUE(std::any_of(table.begin(), table.end(), [](const std::string& l) {
    return l.rfind("bad.off ", 0) == 0 && l.find("failed: cannot read") != std::string::npos;
  })) << batch.out;

  // One JSON object per line and file, in order; python's json reads each.
  const std::vector<std::string> json = lines_of(bytes_of(dir / "r.jsonl"));
  ASSERT_EQ(json.size(), inputs.size());
  for (size_t i = 0; i < json.size(); ++i) {
    EXPECT_NE(json[i].find("\"input\": \"" + (dir / inputs[i]).string() + "\""), std::string::npos) << json[i];
    const bool bad = inputs[i] == "bad.off";
    EXPECT_EQ(json[i].find("\"status\": \"failed\"") != std::string::npos, bad) << json[i];
    if (bad) {
      EXPECT_NE(json[i].find("\"exit_code\": 3"), std::string::npos) << json[i];
    }
  }
  EXPECT_EQ(std::system(("python3 -c 'import json,sys; [json.loads(l) for l in open(sys.argv[1])]' " + shell_path(dir / "r.jsonl")).c_str()), 0);
  fs::remove_all(dir);
}

// What a batch cannot do is refused before any work, as bad usage.
TEST(CliBatch, BadBatchesAreRefusedBeforeAnyWork) {
  const fs::path dir = test::scratch();
  const std::string bunny = shell_path(test::sample_bunny_path());
  for (const auto& [args, reason] : std::vector<std::pair<std::string, std::string>>{
           {bunny + " " + bunny + " -o " + shell_path(dir / "o.ply"), "more than one input mesh given"},
           {bunny + " --out-dir " + shell_path(dir) + " -o " + shell_path(dir / "o.ply"), "give one of them"},
           {bunny + " --out-dir " + shell_path(dir / "missing"), "is not a folder"},
           {bunny + " " + bunny + " --out-dir " + shell_path(dir), "two inputs would both be written to"},
           {bunny + " --out-dir " + shell_path(dir) + " --orient --oriented-output " + shell_path(dir / "p.ply"), "does not go with --out-dir"}}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(fs::is_empty(dir)) << args;
  }
  fs::remove_all(dir);
}
