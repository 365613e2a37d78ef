// The global step of the paper (§II, Eq. 2): the vertex positions that best follow the per-tet
// linear maps L_t, as a least-squares problem whose matrix never changes, factored once.
//
//   E(V) = sum_t w_t || V_t - L_t V_t^0 ||_F^2,   V_t = [v1 - v0, v2 - v0, v3 - v0]   (3 by 3)
//
// V_t holds the three edges from the tet's FIRST vertex T(t,0) (the paper uses its last; the
// choice only relabels vertices). Because L_t is one matrix per tet, E is a weighted graph
// Laplacian over those three edges per tet: its normal matrix K = A^T A depends on the weights and
// the connectivity, never on the positions or on L. So K is factored once, and each iteration
// only assembles the right-hand side and back-substitutes: ONE #free by #free system with three
// right-hand sides (x, y, z), not a 3#free system.
//
//   ArapSolver arap(rest, pinned);             // precomputation: assembly + factorization
//   Points V = arap.solve(L, V_held);          // per iteration: RHS + back-substitution
//
// Inputs:
//   rest    TetMesh, V^0 #V by 3 (mm) and T #T by 4, every tet with positive volume (tet_mesh.h).
//   pinned  vertex indices held in place: they are removed from the unknowns and their terms go
//           to the right-hand side. The optimizer pins the domain vertices on the build plate,
//           which also fixes the rigid motion (E is invariant to translating every vertex).
//           Every connected component of the domain needs at least one pinned vertex, or K is
//           singular: such a component throws std::invalid_argument, unless
//           ArapOptions::anchor_floating_components pins its first vertex for you.
//           Vertices in no tet are held too (nothing determines them).
//   weights #T, w_t >= 0; defaults to the rest volumes (mm^3), as in the paper.
//   anchors #V, a_v >= 0 (mm^3), or empty for none: E gains sum_v a_v || v - v^0 ||^2, a spring
//           from each vertex to its rest position. K_ff gains them on its diagonal, so they are
//           factored with it; a vertex with a_v > 0 also pins its component's rigid motion.
//           The optimizer anchors what the support does not need (support_region.h).
//   L       #T 3 by 3 matrices, one per tet, in the order of T (unitless).
//   V_held  #V by 3; only the rows of held vertices are read: they are copied to the result.
// Output:
//   #V by 3 minimiser of E (mm); held vertices exactly at their V_held rows.
//
// Errors: std::invalid_argument for bad indices, sizes, weights, a rest tet with volume <= 1e-12
// of its longest edge cubed (the local step inverts V_t^0) or a component with no pin;
// std::runtime_error when the factorization fails or a solve returns non-finite values (a
// non-finite L). Every entry point is deterministic: the RHS and the energy sum in an order fixed
// by the mesh, whatever the OpenMP thread count, and BLAS runs on ArapOptions::blas_threads.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/tet_mesh.h"
#include "core/solver/sparse_cholesky.h"

namespace slim {

// V_t = [v1 - v0, v2 - v0, v3 - v0] of one tet (3 by 3, edges as columns): the basis of E above.
// The local step must use the same basis: Q_t = edge_matrix(V, t) * edge_matrix(V0, t)^-1.
inline Eigen::Matrix3d edge_matrix(const Points& V, const Eigen::Matrix<int, 1, 4>& tet) {
  Eigen::Matrix3d E;
  for (int j = 0; j < 3; ++j) E.col(j) = (V.row(tet(j + 1)) - V.row(tet(0))).transpose();
  return E;
}

struct ArapOptions {
  // The factorization's backend (sparse_cholesky.h): Auto (CHOLMOD supernodal when built with
  // it, solved by SupernodalSolver; else Eigen's SimplicialLDLT), Cholmod, CholmodSimplicial or
  // EigenLDLT.
  using Backend = CholeskyBackend;
  Backend backend = Backend::Auto;  // a CHOLMOD backend without CHOLMOD built in throws
  // Threads OpenBLAS may use inside CHOLMOD's factorization (and CHOLMOD's own solve), set for
  // their duration and restored afterwards. 1 (default): results repeat bit for bit whatever the
  // process's BLAS setting (blas_threads.h says why). 0: leave that setting alone.
  int blas_threads = 1;
  // With the CHOLMOD supernodal backend: back-substitute with SupernodalSolver on CHOLMOD's
  // factor (faster for three right-hand sides, see supernodal_solve.h) rather than CHOLMOD's
  // own solve. false is kept for comparison (tests, benchmarks).
  bool own_supernodal_solve = true;
  // A connected component with no pinned vertex: false (default) throws; true pins the
  // component's lowest-index vertex, so the component keeps the position V_held gives it.
  bool anchor_floating_components = false;
};

class ArapSolver {
 public:
  // Precomputation: checks, assembles K over the free vertices and factors it (the only
  // factorization this object ever does). Weights default to the rest volumes.
  ArapSolver(const TetMesh& rest, const std::vector<int>& pinned, const ArapOptions& options = {});
  ArapSolver(const TetMesh& rest, const Eigen::VectorXd& weights, const std::vector<int>& pinned,
             const ArapOptions& options = {});
  ArapSolver(const TetMesh& rest, const Eigen::VectorXd& weights, const std::vector<int>& pinned,
             const Eigen::VectorXd& anchors, const ArapOptions& options = {});
  ~ArapSolver();
  ArapSolver(ArapSolver&&) noexcept;
  ArapSolver& operator=(ArapSolver&&) noexcept;

  // Linear equality constraints every later solve holds (linear_constraints.h), set once after
  // the factorization, which they leave as it is: sum_v <C_k.row(v), V.row(v)> = c_k, each C_k
  // #V by 3 (rows of held vertices count with their V_held positions). solve() then returns E's
  // minimiser under them, response() a displacement within them (sum_v <C_k.row(v), dV.row(v)> =
  // 0). One back-substitution per constraint. The optimizer holds the part's proportions so
  // (rigid_proportions.h). Throws std::invalid_argument for mismatched sizes.
  void set_constraints(const std::vector<Points>& C, const Eigen::VectorXd& c);

  // The global step: assemble_rhs + back_substitute, scattered into #V by 3.
  Points solve(const std::vector<Eigen::Matrix3d>& L, const Points& V_held) const;

  // The displacement a load causes: K_ff^-1 of the free rows of `load` (#V by 3, one force per
  // vertex), scattered into #V by 3 with the held vertices at zero: the direction in which the
  // minimiser moves when the energy gains a term linear in the positions, -sum_v load_v · V_v (a
  // constraint's Lagrange step, whose gradient is the load). One back-substitution.
  Points response(const Points& load) const;

  // solve(L, V_held) and response(load) in one back-substitution of six right-hand sides: one
  // sweep of the factor serves both, which costs little more than one (the sweep is bound by
  // reading the factor). The same values, bit for bit, as the two calls.
  Points solve_with_response(const std::vector<Eigen::Matrix3d>& L, const Points& V_held, const Points& load,
                             Points& response) const;

  // The two halves, public so a benchmark can time the bare back-substitution.
  //   assemble_rhs:    #free by 3, K_ff^-1 of it is the free vertices' solution.
  //   back_substitute: #free by k (k = 3 or 6) -> #free by k solution in the order of
  //                    free_vertices().
  Eigen::MatrixXd assemble_rhs(const std::vector<Eigen::Matrix3d>& L, const Points& V_held) const;
  Eigen::MatrixXd back_substitute(const Eigen::MatrixXd& rhs) const;

  // E(V) for any #V by 3 positions (mm^2 times the weights' unit), the anchors' springs included.
  double energy(const Points& V, const std::vector<Eigen::Matrix3d>& L) const;
  // E of several shapes in one pass over the tets (each #V by 3): the same values, bit for bit,
  // as energy() of each.
  Eigen::VectorXd energies(const std::vector<const Points*>& shapes, const std::vector<Eigen::Matrix3d>& L) const;

  int num_vertices() const;
  int num_tets() const;
  const std::vector<int>& free_vertices() const;  // ascending; row i of the solve's unknowns
  const std::vector<int>& held_vertices() const;  // ascending: pinned, isolated and anchored
  const Eigen::VectorXd& weights() const;         // #T
  std::string backend_name() const;               // for the log, e.g. "CHOLMOD supernodal"
  int factorizations() const;                     // numeric factorizations done: always 1
  static bool cholmod_available();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace slim
