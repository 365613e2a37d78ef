// Which tetrahedral domain the optimizer builds around the surface (embedded_domain.h).
#pragma once

namespace slim {

enum class DomainKind {
  Voxel,  // voxel cells split into Kuhn tets, aligned with the print direction (voxel_domain.h)
  TetGen  // a constrained tetrahedralization of the surface itself (tetgen_domain.h; AGPL-3, optional)
};

}  // namespace slim
