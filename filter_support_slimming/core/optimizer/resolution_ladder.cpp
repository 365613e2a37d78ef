#include "core/optimizer/resolution_ladder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace slim {

std::vector<int> ladder_resolutions(const SlimmingOptions& o, long faces) {
  std::vector<int> rungs{o.resolution};
  const CoherenceOptions c = coherence_of(o);
  if (!c.choose_by_support_model || o.domain != DomainKind::Voxel || o.max_iterations == 0 ||
      faces > c.resolution_ladder_max_faces)
    return rungs;
  for (double multiple : c.resolution_ladder) {
    const int r = static_cast<int>(std::lround(o.resolution * multiple));
    if (std::find(rungs.begin(), rungs.end(), r) == rungs.end()) rungs.push_back(r);
  }
  return rungs;
}

bool prefer(const SlimmingResult& candidate, const SlimmingResult& kept) {
  return candidate.support_after_mm3 < kept.support_after_mm3;
}

std::string ladder_line(const SlimmingResult& r) {
  if (r.resolution == 0) return "the TetGen domain (no voxels)";
  std::string line = std::to_string(r.resolution) + " cells along the longest side";
  if (r.resolution_runs.size() < 2) return line;
  line += "; the least support of";
  const char* separator = " ";
  for (const ResolutionRun& run : r.resolution_runs) {
    char rung[96];
    if (run.refused.empty())
      std::snprintf(rung, sizeof rung, "%s%d (%.6g mm^3)", separator, run.resolution, run.support_after_mm3);
    else
      std::snprintf(rung, sizeof rung, "%s%d (not run: %s)", separator, run.resolution,
                    run.refused.find("memory") != std::string::npos ? "too large for the memory budget" : "it failed");
    line += rung;
    separator = ", ";
  }
  return line + " (the support model's estimates of the results)";
}

}  // namespace slim
