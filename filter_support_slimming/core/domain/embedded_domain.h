// The optimizer's domain with the surface embedded in it: the voxel or TetGen tet mesh, which of
// its vertices rest on the build plate, and the embedding (paper §II).
//
//   EmbeddedDomain domain = embedded_domain(surface, d, kind, resolution, max_memory_bytes, report);
//
// Inputs
//   surface  a checked surface (checked_surface.h), #V by 3 mm, #F by 3.
//   d        the unit print direction.
//   kind, resolution  the domain (Voxel or TetGen) and, for voxels, the cells along the longest side.
//   max_memory_bytes  the run's memory budget (none: no budget), which caps the voxel domain's own
//            worst-case guard (voxel_budget.h).
//   report   called once between the domain and the embedding (fraction 0.02); it may throw
//            (Cancelled) to stop there.
// Output: EmbeddedDomain below, with the time of each stage.
// Errors: std::invalid_argument for a voxel grid over the budget (DomainTooLarge), for the TetGen
// domain on a surface TetGen cannot take or with vertices no face uses (TetGen meshes only the
// referenced ones, so they could not be embedded), or for a vertex outside the domain;
// std::runtime_error from TetGen's child process.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/domain/domain_options.h"
#include "core/domain/embedding.h"
#include "core/geometry/checked_surface.h"
#include "core/geometry/tet_mesh.h"

namespace slim {

struct EmbeddedDomain {
  TetMesh mesh;                                    // #DV by 3, #DT by 4, every tet positive
  Eigen::Array<bool, Eigen::Dynamic, 1> on_plate;  // #DV
  Embedding embedding;                             // the surface in mesh
  double domain_seconds = 0.0, embedding_seconds = 0.0;
};

EmbeddedDomain embedded_domain(const CheckedSurface& surface, const Eigen::Vector3d& d, DomainKind kind, int resolution,
                               std::optional<double> max_memory_bytes, const std::function<void(double, const std::string&)>& report);

}  // namespace slim
