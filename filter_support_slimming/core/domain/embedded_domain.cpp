#include "core/domain/embedded_domain.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "core/domain/tetgen_domain.h"
#include "core/domain/voxel_domain.h"

namespace slim {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// TetGen meshes only the vertices that faces use (tetgen_domain.h): a stray vertex could not be
// embedded, so say so now rather than "outside the domain" after TetGen has run.
void require_referenced_vertices(const Surface& input) {
  std::vector<bool> used(static_cast<size_t>(input.V.rows()), false);
  for (Eigen::Index f = 0; f < input.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<size_t>(input.F(f, k))] = true;
  const auto stray = std::find(used.begin(), used.end(), false);
  if (stray != used.end())
    throw std::invalid_argument("vertex " + std::to_string(stray - used.begin()) + " belongs to no face (" +
                                std::to_string(std::count(used.begin(), used.end(), false)) +
                                " such vertices), and the TetGen domain cannot hold it: remove the unreferenced "
                                "vertices or use the voxel domain");
}

// What the embedding locates the surface in: the voxel domain itself (its grid finds the tets),
// or TetGen's mesh.
const VoxelDomain& locating(const VoxelDomain& d) { return d; }
const TetMesh& locating(const TetgenDomain& d) { return d.mesh; }

template <class Build>
EmbeddedDomain build_and_embed(const CheckedSurface& surface, Build&& build,
                               const std::function<void(double, const std::string&)>& report) {
  EmbeddedDomain domain;
  auto start = std::chrono::steady_clock::now();
  auto built = build();
  domain.domain_seconds = seconds_since(start);
  report(0.02, "embedding the surface");
  start = std::chrono::steady_clock::now();
  domain.embedding = embed_surface(surface, locating(built));
  domain.embedding_seconds = seconds_since(start);
  domain.mesh = std::move(built.mesh);
  domain.on_plate = std::move(built.on_plate);
  return domain;
}

}  // namespace

EmbeddedDomain embedded_domain(const CheckedSurface& surface, const Eigen::Vector3d& d, DomainKind kind, int resolution,
                               std::optional<double> max_memory_bytes, const std::function<void(double, const std::string&)>& report) {
  if (kind == DomainKind::Voxel) {
    VoxelDomainOptions vo;
    vo.resolution = resolution;
    if (max_memory_bytes) vo.max_bytes = std::min(vo.max_bytes, *max_memory_bytes);
    return build_and_embed(surface, [&] { return voxel_domain(surface, d, vo); }, report);
  }
  require_referenced_vertices(surface.get());
  return build_and_embed(surface, [&] { return tetgen_domain(surface, d); }, report);
}

}  // namespace slim
