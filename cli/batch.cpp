#include "batch.h"

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "summary.h"

namespace slim::cli {

namespace {

struct Row {
  std::string in, out;
  bool failed = false;
  int exit_code = 0;
  std::string error;
  FileRun run;
};

std::string status_of(const Row& r) {
  if (r.failed) return "failed: " + r.error;
  if (r.run.unchanged) return "unchanged: " + r.run.stop_reason;
  return "done";
}

void print_table(const std::vector<Row>& rows) {
  std::printf("\n%-28s %26s %9s %9s %8s %8s  %s\n", "file", "support (model), mm^3", "Hausdorff", "volume", "height", "creases",
              "status");
  int done = 0;
  for (const Row& r : rows) {
    const std::string name = std::filesystem::path(r.in).filename().string();
    if (r.failed) {
      std::printf("%-28s %26s %9s %9s %8s %8s  %s\n", name.c_str(), "-", "-", "-", "-", "-", status_of(r).c_str());
      continue;
    }
    ++done;
    const SlimmingFigures& f = r.run.figures;
    char support[64];
    std::snprintf(support, sizeof support, "%.4g -> %.4g (%+.1f%%)", f.support_estimate_before_mm3, f.support_estimate_after_mm3,
                  f.support_change_pct);
    std::printf("%-28s %26s %8.2f%% %+8.2f%% %+7.2f%% %7.2f%%  %s\n", name.c_str(), support, f.hausdorff_pct, f.volume_change_pct,
                f.height_change_pct, f.crease_share_pct, status_of(r).c_str());
  }
  std::printf("%d of %zu files done", done, rows.size());
  if (done < static_cast<int>(rows.size())) std::printf(", %zu failed", rows.size() - done);
  std::printf(" (Hausdorff: %% of the bbox diagonal; creases: %% of the edge length)\n");
}

// The failure as one JSON line.
std::string failure_json(const Row& r) {
  return "{ \"input\": " + json_string(r.in) + ", \"output\": " + json_string(r.out) + ", \"status\": \"failed\", \"error\": " +
         json_string(r.error) + ", \"exit_code\": " + std::to_string(r.exit_code) + " }";
}

}  // namespace

std::string batch_output(const std::string& out_dir, const std::string& in) {
  const std::filesystem::path p(in);
  return (std::filesystem::path(out_dir) / (p.stem().string() + "_slimmed" + p.extension().string())).string();
}

int run_batch(const CliOptions& c) {
  std::set<std::string> outputs;
  for (const std::string& in : c.inputs)
    if (!outputs.insert(std::filesystem::absolute(batch_output(c.out_dir, in)).string()).second)
      die("two inputs would both be written to " + batch_output(c.out_dir, in) + ": rename one, or run them apart");
  std::vector<Row> rows;
  std::string lines;
  for (const std::string& in : c.inputs) {
    Row r;
    r.in = in, r.out = batch_output(c.out_dir, in);
    try {
      r.run = slim_file(c, in, r.out, !c.quiet);
      const std::string json = one_line(r.run.report_json);
      lines += json.substr(0, json.size() - 2) + ", \"status\": " + (r.run.unchanged ? "\"unchanged\"" : "\"done\"") + " }\n";
    } catch (const Refusal& e) {
      r.failed = true, r.exit_code = e.code, r.error = e.what();
      std::fprintf(stderr, "support-slim: %s\n", e.what());
      lines += failure_json(r) + "\n";
    }
    rows.push_back(r);
  }
  print_table(rows);
  if (!c.report.empty()) {
    try {
      write_text(c.report, lines, "the report");
    } catch (const std::exception& e) {
      die(e.what(), kExitRunFailed);
    }
  }
  for (const Row& r : rows)
    if (r.failed) return kExitRunFailed;
  return 0;
}

}  // namespace slim::cli
