#include "core/optimizer/resolution_ladder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace slim {

std::vector<int> ladder_resolutions(const SlimmingOptions& options, long faces) {
  const SlimmingOptions o = method_applied(options);
  std::vector<int> rungs{o.resolution};
  if (o.result.judge != ResultJudge::SupportModel || o.domain != DomainKind::Voxel || o.steps.max_iterations == 0 ||
      faces > o.ladder.max_faces)
    return rungs;
  for (double multiple : o.ladder.multiples) {
    const int r = static_cast<int>(std::lround(o.resolution * multiple));
    if (std::find(rungs.begin(), rungs.end(), r) == rungs.end()) rungs.push_back(r);
  }
  return rungs;
}

bool needs_less_support(const SlimmingResult& candidate, const SlimmingResult& kept) {
  return candidate.support_after_mm3 && kept.support_after_mm3 && *candidate.support_after_mm3 < *kept.support_after_mm3;
}

std::string ladder_line(const SlimmingResult& r) {
  if (r.resolution == 0) return "the TetGen domain (no voxels)";
  std::string line = std::to_string(r.resolution) + " cells along the longest side";
  if (r.resolution_runs.size() < 2) return line;
  line += "; the least support of";
  const char* separator = " ";
  for (const ResolutionRun& run : r.resolution_runs) {
    char rung[96];
    if (run.refused.empty() && run.support_after_mm3)
      std::snprintf(rung, sizeof rung, "%s%d (%.6g mm^3)", separator, run.resolution, *run.support_after_mm3);
    else if (run.refused.empty())
      std::snprintf(rung, sizeof rung, "%s%d (not measured)", separator, run.resolution);
    else
      std::snprintf(rung, sizeof rung, "%s%d (not run: %s)", separator, run.resolution,
                    run.refused.find("memory") != std::string::npos ? "too large for the memory budget" : "it failed");
    line += rung;
    separator = ", ";
  }
  return line + " (the support model's estimates of the results)";
}

}  // namespace slim
