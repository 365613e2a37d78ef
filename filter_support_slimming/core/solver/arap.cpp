#include "core/solver/arap.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "core/solver/linear_constraints.h"
#include "core/solver/sparse_cholesky.h"
#include "core/utilities/union_find.h"

namespace slim {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The energy is summed over fixed blocks of tets, then the blocks in order: the same bits for
// any thread count.
constexpr int kEnergyBlock = 4096;
// Fewer free vertices than this are gathered on one thread: the work (a few loads and adds a
// vertex) is then smaller than waking a thread team, and on a busy machine a team can wait a whole
// time slice.
constexpr int kParallelRows = 4096;

}  // namespace

// One factorization, behind whichever backend the options chose.
struct ArapSolver::Impl {
  int nv = 0, nt = 0;
  Tets T;
  Eigen::VectorXd w;                             // #T
  Eigen::VectorXd anchor;                        // #V springs to the rest positions; empty: none
  Points anchor_target;                          // #V rest positions, when anchored
  std::vector<Eigen::Matrix<double, 3, 4>> rest;  // per tet [-(e1+e2+e3), e1, e2, e3] at rest
  std::vector<int> free_index;                   // #V: row in the unknowns, -1 when held
  std::vector<int> free_vertices, held_vertices;
  // CSR incidence of the free vertices: entries tet * 4 + corner, tets ascending; inc_held marks
  // the entries whose basis edges end at a held vertex (their terms go to the right-hand side).
  std::vector<int> inc_begin, inc;
  std::vector<char> inc_held;
  // assemble_rhs's per-tet gradient terms (#T of 3 by 4, 96 bytes a tet), kept between calls:
  // allocated afresh, its pages cost more than the assembly itself.
  mutable std::mutex workspace_mutex;
  mutable std::vector<Eigen::Matrix<double, 3, 4>> gradient;

  ArapOptions options;
  int factorizations = 0;
  std::unique_ptr<SparseCholesky> cholesky;  // of K_ff; none when every vertex is held
  // set_constraints(): their free rows, their held rows and their values.
  std::unique_ptr<LinearConstraints> constraints;
  std::vector<Points> constraint_held;
  Eigen::VectorXd constraint_values;

  // Everything a constructor does: store and check, split, index, factor once, size the workspace.
  void setup(const TetMesh& mesh, const ArapOptions& opts, const Eigen::VectorXd* weights,
             const std::vector<int>& pinned, const Eigen::VectorXd* anchors);
  void store_anchors(const TetMesh& mesh, const Eigen::VectorXd& anchors);
  void check_and_store(const TetMesh& mesh, const Eigen::VectorXd* weights);
  void split_vertices(const std::vector<int>& pinned);
  void build_incidence();
  SparseMatrix free_matrix() const;
  void check_L(const std::vector<Eigen::Matrix3d>& L) const;
  Eigen::MatrixXd free_rows(const Points& load) const;  // #free by 3: the load's free rows
  // The constraints' values for the free rows, given the held vertices' positions.
  Eigen::VectorXd free_values(const Points& V_held) const;
};

void ArapSolver::Impl::check_and_store(const TetMesh& mesh, const Eigen::VectorXd* weights) {
  nv = static_cast<int>(mesh.V.rows());
  nt = static_cast<int>(mesh.T.rows());
  if (nt == 0) throw std::invalid_argument("ArapSolver: the domain has no tets");
  if (!mesh.V.allFinite()) throw std::invalid_argument("ArapSolver: non-finite rest position");
  if ((mesh.T.array() < 0).any() || (mesh.T.array() >= nv).any())
    throw std::invalid_argument("ArapSolver: a tet indexes outside the vertex list");
  if (weights && weights->size() != nt)
    throw std::invalid_argument("ArapSolver: expected one weight per tet");
  T = mesh.T;
  w.resize(nt);
  rest.resize(static_cast<size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    const Eigen::Matrix3d E = edge_matrix(mesh.V, T.row(t));
    const double vol = E.determinant() / 6.0;
    const double longest = E.colwise().norm().maxCoeff();
    // Relative to the tet's own size, so the test does not depend on the units.
    if (!(vol > 1e-12 * longest * longest * longest)) {
      std::ostringstream msg;
      msg << "ArapSolver: rest tet " << t << " has volume " << vol
          << (vol < 0 ? " (inverted)" : " (degenerate)") << "; the domain must be positively oriented";
      throw std::invalid_argument(msg.str());
    }
    rest[static_cast<size_t>(t)] << -E.rowwise().sum(), E;
    w(t) = weights ? (*weights)(t) : vol;
    if (!std::isfinite(w(t)) || w(t) < 0.0) {
      std::ostringstream msg;
      msg << "ArapSolver: weight " << w(t) << " of tet " << t << " is not finite and >= 0";
      throw std::invalid_argument(msg.str());
    }
  }
}

void ArapSolver::Impl::split_vertices(const std::vector<int>& pinned) {
  std::vector<char> held(static_cast<size_t>(nv), 0);
  for (int p : pinned) {
    if (p < 0 || p >= nv) throw std::invalid_argument("ArapSolver: pinned vertex index out of range");
    held[static_cast<size_t>(p)] = 1;
  }
  // Components of the edges that carry weight; a vertex on none of them is held (nothing in E
  // determines it), and every other component needs a held vertex or K is singular.
  UnionFind comp(nv);
  std::vector<char> used(static_cast<size_t>(nv), 0);
  for (int t = 0; t < nt; ++t) {
    if (!(w(t) > 0.0)) continue;
    for (int j = 0; j < 4; ++j) used[static_cast<size_t>(T(t, j))] = 1;
    for (int j = 1; j < 4; ++j) comp.join(T(t, 0), T(t, j));
  }
  std::vector<char> root_held(static_cast<size_t>(nv), 0);
  for (int v = 0; v < nv; ++v) {
    if (!used[static_cast<size_t>(v)]) held[static_cast<size_t>(v)] = 1;
    if (held[static_cast<size_t>(v)]) root_held[static_cast<size_t>(comp.find(v))] = 1;
    if (anchor.size() && anchor(v) > 0.0) root_held[static_cast<size_t>(comp.find(v))] = 1;
  }
  for (int v = 0; v < nv; ++v) {
    if (comp.find(v) != v || root_held[static_cast<size_t>(v)]) continue;
    if (!options.anchor_floating_components) {
      std::ostringstream msg;
      msg << "ArapSolver: the component containing vertex " << v
          << " has no pinned vertex, so its position is undetermined; pin one of its vertices";
      throw std::invalid_argument(msg.str());
    }
    held[static_cast<size_t>(v)] = 1;  // v is the component's lowest index (union_find.h)
  }
  free_index.assign(static_cast<size_t>(nv), -1);
  for (int v = 0; v < nv; ++v) {
    if (held[static_cast<size_t>(v)]) {
      held_vertices.push_back(v);
    } else {
      free_index[static_cast<size_t>(v)] = static_cast<int>(free_vertices.size());
      free_vertices.push_back(v);
    }
  }
}

void ArapSolver::Impl::build_incidence() {
  const size_t nf = free_vertices.size();
  inc_begin.assign(nf + 1, 0);
  for (int t = 0; t < nt; ++t)
    for (int j = 0; j < 4; ++j) {
      const int f = free_index[static_cast<size_t>(T(t, j))];
      if (f >= 0) ++inc_begin[static_cast<size_t>(f) + 1];
    }
  for (size_t f = 0; f < nf; ++f) inc_begin[f + 1] += inc_begin[f];
  inc.resize(static_cast<size_t>(inc_begin[nf]));
  std::vector<int> fill(inc_begin.begin(), inc_begin.end() - 1);
  for (int t = 0; t < nt; ++t)  // tets ascending: the summation order of assemble_rhs
    for (int j = 0; j < 4; ++j) {
      const int f = free_index[static_cast<size_t>(T(t, j))];
      if (f >= 0) inc[static_cast<size_t>(fill[static_cast<size_t>(f)]++)] = 4 * t + j;
    }
  inc_held.assign(inc.size(), 0);
  for (size_t k = 0; k < inc.size(); ++k) {
    const int t = inc[k] / 4, j = inc[k] % 4;
    for (int o = (j == 0 ? 1 : 0); o < (j == 0 ? 4 : 1); ++o)
      if (free_index[static_cast<size_t>(T(t, o))] < 0) inc_held[k] = 1;
  }
}

// K_ff, lower triangle: each tet adds w_t to the Laplacian of its edges (v0, vj), j = 1..3.
SparseMatrix ArapSolver::Impl::free_matrix() const {
  const int nf = static_cast<int>(free_vertices.size());
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(nf);
  std::vector<Eigen::Triplet<double, int>> trip;
  trip.reserve(static_cast<size_t>(3 * nt + nf));
  for (int t = 0; t < nt; ++t) {
    const int a = free_index[static_cast<size_t>(T(t, 0))];
    for (int j = 1; j < 4; ++j) {
      const int b = free_index[static_cast<size_t>(T(t, j))];
      if (a >= 0) diag(a) += w(t);
      if (b >= 0) diag(b) += w(t);
      if (a >= 0 && b >= 0) trip.emplace_back(std::max(a, b), std::min(a, b), -w(t));
    }
  }
  if (anchor.size())
    for (int f = 0; f < nf; ++f) diag(f) += anchor(free_vertices[static_cast<size_t>(f)]);
  for (int f = 0; f < nf; ++f) trip.emplace_back(f, f, diag(f));
  SparseMatrix K(nf, nf);
  K.setFromTriplets(trip.begin(), trip.end());
  return K;
}

void ArapSolver::Impl::check_L(const std::vector<Eigen::Matrix3d>& L) const {
  if (static_cast<int>(L.size()) != nt) throw std::invalid_argument("ArapSolver: expected one L per tet");
}

void ArapSolver::Impl::store_anchors(const TetMesh& mesh, const Eigen::VectorXd& anchors) {
  if (anchors.size() == 0) return;
  if (anchors.size() != nv) throw std::invalid_argument("ArapSolver: expected one anchor weight per vertex");
  if (!anchors.allFinite() || (anchors.array() < 0.0).any())
    throw std::invalid_argument("ArapSolver: anchor weights must be finite and >= 0");
  anchor = anchors;
  anchor_target = mesh.V;
}

void ArapSolver::Impl::setup(const TetMesh& mesh, const ArapOptions& opts, const Eigen::VectorXd* weights,
                             const std::vector<int>& pinned, const Eigen::VectorXd* anchors) {
  options = opts;
  check_and_store(mesh, weights);
  if (anchors) store_anchors(mesh, *anchors);
  split_vertices(pinned);
  build_incidence();
  if (!free_vertices.empty()) {
    SparseCholeskyOptions o;
    o.backend = options.backend;
    o.blas_threads = options.blas_threads;
    o.own_supernodal_solve = options.own_supernodal_solve;
    cholesky = std::make_unique<SparseCholesky>(free_matrix(), o);
    ++factorizations;
  }
  gradient.assign(static_cast<size_t>(nt), Eigen::Matrix<double, 3, 4>::Zero());  // its pages, now
}

ArapSolver::ArapSolver(const TetMesh& rest, const std::vector<int>& pinned, const ArapOptions& options)
    : impl_(std::make_unique<Impl>()) { impl_->setup(rest, options, nullptr, pinned, nullptr); }
ArapSolver::ArapSolver(const TetMesh& rest, const Eigen::VectorXd& weights, const std::vector<int>& pinned,
                       const ArapOptions& options)
    : impl_(std::make_unique<Impl>()) { impl_->setup(rest, options, &weights, pinned, nullptr); }
ArapSolver::ArapSolver(const TetMesh& rest, const Eigen::VectorXd& weights, const std::vector<int>& pinned,
                       const Eigen::VectorXd& anchors, const ArapOptions& options)
    : impl_(std::make_unique<Impl>()) { impl_->setup(rest, options, &weights, pinned, &anchors); }
ArapSolver::~ArapSolver() = default;
ArapSolver::ArapSolver(ArapSolver&&) noexcept = default;
ArapSolver& ArapSolver::operator=(ArapSolver&&) noexcept = default;

// Row f of K_ff x_f = b_f - K_fh x_h for the free vertex v = free_vertices[f]:
//   b:    the gradient terms, w_t L_t e_j at corner j (j = 1..3) and -w_t L_t (e1+e2+e3) at corner 0;
//   K_fh: w_t times each held vertex across one of v's basis edges.
// Each row is gathered by one thread through the incidence list, in ascending tet order.
Eigen::MatrixXd ArapSolver::assemble_rhs(const std::vector<Eigen::Matrix3d>& L, const Points& V_held) const {
  const Impl& m = *impl_;
  m.check_L(L);
  if (V_held.rows() != m.nv) throw std::invalid_argument("ArapSolver: V_held must have one row per vertex");
  const int nf = static_cast<int>(m.free_vertices.size());
  // Each tet's four gradient terms once (w_t L_t times the rest corners), read by its corners'
  // rows below: the tets stream in order here, and each row reads 24 bytes per incidence.
  const std::lock_guard<std::mutex> lock(m.workspace_mutex);
  std::vector<Eigen::Matrix<double, 3, 4>>& gradient = m.gradient;  // sized by setup()
#pragma omp parallel for schedule(static) if (m.nt >= kParallelRows)
  for (int t = 0; t < m.nt; ++t) {
    const double wt = m.w(t);
    for (int j = 0; j < 4; ++j)
      gradient[static_cast<size_t>(t)].col(j) = wt * (L[static_cast<size_t>(t)] * m.rest[static_cast<size_t>(t)].col(j));
  }
  Eigen::MatrixXd rhs(nf, 3);
#pragma omp parallel for schedule(static) if (nf >= kParallelRows)
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int k = m.inc_begin[static_cast<size_t>(f)]; k < m.inc_begin[static_cast<size_t>(f) + 1]; ++k) {
      const int t = m.inc[static_cast<size_t>(k)] / 4, j = m.inc[static_cast<size_t>(k)] % 4;
      b += gradient[static_cast<size_t>(t)].col(j);
      // The other ends of v's basis edges that are held: v1..v3 from corner 0, v0 from the others.
      if (m.inc_held[static_cast<size_t>(k)] == 0) continue;
      const double wt = m.w(t);
      for (int o = (j == 0 ? 1 : 0); o < (j == 0 ? 4 : 1); ++o) {
        const int u = m.T(t, o);
        if (m.free_index[static_cast<size_t>(u)] < 0) b += wt * V_held.row(u).transpose();
      }
    }
    if (m.anchor.size()) {
      const int v = m.free_vertices[static_cast<size_t>(f)];
      b += m.anchor(v) * m.anchor_target.row(v).transpose();
    }
    rhs.row(f) = b.transpose();
  }
  return rhs;
}

Eigen::MatrixXd ArapSolver::back_substitute(const Eigen::MatrixXd& rhs) const {
  const Impl& m = *impl_;
  if (rhs.rows() != static_cast<Eigen::Index>(m.free_vertices.size()) || (rhs.cols() != 3 && rhs.cols() != 6))
    throw std::invalid_argument("ArapSolver: the right-hand side must be #free by 3 or by 6");
  if (m.free_vertices.empty()) return Eigen::MatrixXd(0, rhs.cols());
  Eigen::MatrixXd x;
  if (!m.cholesky->solve(rhs, x))
    throw std::runtime_error("ArapSolver: the global step produced non-finite positions (non-finite L?)");
  return x;
}

void ArapSolver::set_constraints(const std::vector<Points>& C, const Eigen::VectorXd& c) {
  Impl& m = *impl_;
  if (c.size() != static_cast<Eigen::Index>(C.size()))
    throw std::invalid_argument("ArapSolver: expected one value per constraint");
  std::vector<Eigen::MatrixXd> free;
  m.constraint_held.clear();
  for (const Points& Ck : C) {
    if (Ck.rows() != m.nv || Ck.cols() != 3) throw std::invalid_argument("ArapSolver: a constraint must be #V by 3");
    free.push_back(m.free_rows(Ck));
    Points held = Points::Zero(m.nv, 3);
    for (int v : m.held_vertices) held.row(v) = Ck.row(v);
    m.constraint_held.push_back(std::move(held));
  }
  m.constraint_values = c;
  m.constraints = std::make_unique<LinearConstraints>(std::move(free), [this](const Eigen::MatrixXd& rhs) { return back_substitute(rhs); });
}

Eigen::VectorXd ArapSolver::Impl::free_values(const Points& V_held) const {
  Eigen::VectorXd c = constraint_values;
  for (size_t k = 0; k < constraint_held.size(); ++k)
    c(static_cast<Eigen::Index>(k)) -= constraint_held[k].cwiseProduct(V_held).sum();
  return c;
}

Points ArapSolver::solve(const std::vector<Eigen::Matrix3d>& L, const Points& V_held) const {
  Eigen::MatrixXd x = back_substitute(assemble_rhs(L, V_held));
  if (impl_->constraints) impl_->constraints->project(x, impl_->free_values(V_held));
  Points V = V_held;
  for (size_t f = 0; f < impl_->free_vertices.size(); ++f)
    V.row(impl_->free_vertices[f]) = x.row(static_cast<Eigen::Index>(f));
  return V;
}

Eigen::MatrixXd ArapSolver::Impl::free_rows(const Points& load) const {
  if (load.rows() != nv) throw std::invalid_argument("ArapSolver: the load must have one row per vertex");
  Eigen::MatrixXd rhs(static_cast<Eigen::Index>(free_vertices.size()), 3);
  for (size_t f = 0; f < free_vertices.size(); ++f) rhs.row(static_cast<Eigen::Index>(f)) = load.row(free_vertices[f]);
  return rhs;
}

Points ArapSolver::response(const Points& load) const {
  const Impl& m = *impl_;
  Eigen::MatrixXd x = back_substitute(m.free_rows(load));
  if (m.constraints) m.constraints->project(x, Eigen::VectorXd::Zero(m.constraints->size()));
  Points V = Points::Zero(m.nv, 3);
  for (size_t f = 0; f < m.free_vertices.size(); ++f) V.row(m.free_vertices[f]) = x.row(static_cast<Eigen::Index>(f));
  return V;
}

Points ArapSolver::solve_with_response(const std::vector<Eigen::Matrix3d>& L, const Points& V_held, const Points& load,
                                       Points& response) const {
  const Impl& m = *impl_;
  const Eigen::Index nf = static_cast<Eigen::Index>(m.free_vertices.size());
  Eigen::MatrixXd rhs(nf, 6);
  rhs.leftCols<3>() = assemble_rhs(L, V_held);
  rhs.rightCols<3>() = m.free_rows(load);
  Eigen::MatrixXd x = back_substitute(rhs);
  if (m.constraints) {
    m.constraints->project(x.leftCols<3>(), m.free_values(V_held));
    m.constraints->project(x.rightCols<3>(), Eigen::VectorXd::Zero(m.constraints->size()));
  }
  Points V = V_held;
  response = Points::Zero(m.nv, 3);
  for (Eigen::Index f = 0; f < nf; ++f) {
    V.row(m.free_vertices[static_cast<size_t>(f)]) = x.block<1, 3>(f, 0);
    response.row(m.free_vertices[static_cast<size_t>(f)]) = x.block<1, 3>(f, 3);
  }
  return V;
}

double ArapSolver::energy(const Points& V, const std::vector<Eigen::Matrix3d>& L) const {
  return energies({&V}, L)(0);
}

Eigen::VectorXd ArapSolver::energies(const std::vector<const Points*>& shapes, const std::vector<Eigen::Matrix3d>& L) const {
  const Impl& m = *impl_;
  m.check_L(L);
  const int count = static_cast<int>(shapes.size());
  for (const Points* V : shapes)
    if (!V || V->rows() != m.nv) throw std::invalid_argument("ArapSolver: V must have one row per vertex");
  const int blocks = (m.nt + kEnergyBlock - 1) / kEnergyBlock;
  Eigen::MatrixXd partial = Eigen::MatrixXd::Zero(count, blocks);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (int b = 0; b < blocks; ++b) {
    for (int t = b * kEnergyBlock; t < std::min(m.nt, (b + 1) * kEnergyBlock); ++t) {
      const Eigen::Matrix3d R = L[static_cast<size_t>(t)] * m.rest[static_cast<size_t>(t)].rightCols<3>();
      for (int k = 0; k < count; ++k) partial(k, b) += m.w(t) * (edge_matrix(*shapes[static_cast<size_t>(k)], m.T.row(t)) - R).squaredNorm();
    }
  }
  Eigen::VectorXd e = Eigen::VectorXd::Zero(count);
  for (int b = 0; b < blocks; ++b) e += partial.col(b);
  if (m.anchor.size())
    for (int k = 0; k < count; ++k)
      e(k) += (m.anchor.array() * (*shapes[static_cast<size_t>(k)] - m.anchor_target).rowwise().squaredNorm().array()).sum();
  return e;
}

int ArapSolver::num_vertices() const { return impl_->nv; }
int ArapSolver::num_tets() const { return impl_->nt; }
const std::vector<int>& ArapSolver::free_vertices() const { return impl_->free_vertices; }
const std::vector<int>& ArapSolver::held_vertices() const { return impl_->held_vertices; }
const Eigen::VectorXd& ArapSolver::weights() const { return impl_->w; }
std::string ArapSolver::backend_name() const {
  return impl_->cholesky ? impl_->cholesky->backend_name() : std::string("none (every vertex held)");
}
int ArapSolver::factorizations() const { return impl_->factorizations; }

bool ArapSolver::cholmod_available() { return SparseCholesky::cholmod_available(); }

}  // namespace slim
