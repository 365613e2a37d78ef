// eval/studies/frontier-summary.sh: the medians, extremes and agreement counts it prints for a
// frontier table, against the same figures computed here from the rows it was given.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.h"
#include "support/source_paths.h"

using slim::test::run_command;
using slim::test::shell_quote;

namespace {

struct Row {
  std::string kind, half;
  double prusa = 0.0, cura = 0.0, affine = 0.0, folds = 0.0;
  bool cura_missing = false;
};

std::string fixed(double x, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, x);
  return text;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

// The summary's cells for one kind and half, split at '|' (cell 0 is the empty text before the
// first bar).
std::vector<std::string> summary_row(const std::string& table, const std::string& kind, const std::string& half) {
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::istringstream parts(line);
    for (std::string cell; std::getline(parts, cell, '|');) {
      cell.erase(0, cell.find_first_not_of(' '));
      cell.erase(cell.find_last_not_of(' ') + 1);
      cells.push_back(cell);
    }
    if (cells.size() > 5 && cells[3] == kind && cells[4] == half) return cells;
  }
  return {};
}

}  // namespace

TEST(FrontierSummary, MediansWorstBestAndAgreementMatchTheRows) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> change(-40.0, 8.0), small(0.0, 1.0);
  std::vector<Row> rows;
  for (int i = 0; i < 37; ++i) {
    Row r;
    r.kind = i % 3 ? "organic" : "cad";
    r.half = i % 2 ? "tune" : "check";
    r.prusa = std::round(change(rng) * 10.0) / 10.0;
    r.cura = std::round(change(rng) * 10.0) / 10.0;
    r.cura_missing = i % 11 == 5;
    r.affine = std::round(small(rng) * 100.0) / 100.0;
    r.folds = i % 7 == 3 ? 2.0 : 0.0;
    rows.push_back(r);
  }
  const std::string path = std::string(SLIM_EVAL_OUT_DIR) + "/frontier_summary_input.tsv";
  {
    std::ofstream tsv(path);
    // The columns in another order than frontier.sh writes them: the script finds them by name.
    tsv << "half\tmodel\tprusa_change_pct\tkind\tmethod\tbudget_pct\tcura_change_pct\taffine_departure_pct\tfolded_faces\n";
    for (size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      tsv << r.half << "\tm" << i << "\t" << fixed(r.prusa, 1) << "\t" << r.kind << "\tcoherent\t5\t"
          << (r.cura_missing ? "n/a" : fixed(r.cura, 1)) << "\t" << fixed(r.affine, 2) << "\t" << r.folds << "\n";
    }
  }
  const auto run = run_command(shell_quote(slim::test::source_dir() + "/eval/studies/frontier-summary.sh") + " " + shell_quote(path));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const std::string kind : {"organic", "cad"}) {
    for (const std::string half : {"tune", "check", "both"}) {
      std::vector<double> prusa, cura, affine, folds;
      int agree = 0;
      for (const Row& r : rows) {
        if (r.kind != kind || (half != "both" && r.half != half)) continue;
        prusa.push_back(r.prusa);
        affine.push_back(r.affine);
        folds.push_back(r.folds);
        if (r.cura_missing) continue;
        cura.push_back(r.cura);
        agree += r.prusa * r.cura > 0.0 && std::abs(r.cura) >= 0.5 * std::abs(r.prusa);
      }
      const std::vector<std::string> cells = summary_row(run.output, kind, half);
      ASSERT_EQ(cells.size(), 19u) << kind << " " << half << "\n" << run.output;
      EXPECT_EQ(cells[5], std::to_string(prusa.size()));
      EXPECT_EQ(cells[6], fixed(median(prusa), 1)) << kind << " " << half;
      EXPECT_EQ(cells[7], fixed(*std::max_element(prusa.begin(), prusa.end()), 1));
      EXPECT_EQ(cells[8], fixed(*std::min_element(prusa.begin(), prusa.end()), 1));
      EXPECT_EQ(cells[9], fixed(median(cura), 1));
      EXPECT_EQ(cells[10], fixed(*std::max_element(cura.begin(), cura.end()), 1));
      EXPECT_EQ(cells[11], std::to_string(agree) + " of " + std::to_string(cura.size()));
      EXPECT_EQ(cells[12], "n/a");  // no Hausdorff column in the table
      EXPECT_EQ(cells[15], fixed(*std::max_element(affine.begin(), affine.end()), 2));
      EXPECT_EQ(cells[18], fixed(*std::max_element(folds.begin(), folds.end()), 0));
    }
  }
}

TEST(FrontierSummary, RefusesAMissingTable) {
  const auto run = run_command(shell_quote(slim::test::source_dir() + "/eval/studies/frontier-summary.sh") + " /nonexistent.tsv");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find("usage"), std::string::npos) << run.output;
}
