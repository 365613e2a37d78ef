#include "core/optimizer/local_step.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "core/platform/parallel_for.h"
#include "core/rotation/axis_rotation.h"
#include "core/rotation/min_rotation.h"
#include "core/rotation/near_repeats.h"
#include "core/rotation/polar.h"
#include "core/solver/arap.h"

namespace slim {

TetPieces constraint_pieces(const Embedding& emb, Eigen::Index tets, const std::vector<bool>& plate,
                            const Points& rest_normals) {
  TetPieces pieces(static_cast<size_t>(tets));
  parallel_for(static_cast<int>(tets), [&](int t) {
    auto& mine = pieces[static_cast<size_t>(t)];
    for (int p = emb.tet_face_offsets(t); p < emb.tet_face_offsets(t + 1); ++p) {
      const int f = emb.tet_faces(p);
      if (plate[static_cast<size_t>(f)] || emb.tet_face_areas(p) <= 0.0 || rest_normals.row(f).squaredNorm() == 0.0)
        continue;
      mine.emplace_back(f, emb.tet_face_areas(p));
    }
    if (mine.size() < 2) return;
    // Normals within kPieceMergeTolerance are one constraint: a piece joins the first such piece
    // before it, which carries their area. Rotations keep the distances, so the merge made at
    // rest holds in every iteration.
    Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(mine.size()));
    for (size_t i = 0; i < mine.size(); ++i) normals.col(static_cast<Eigen::Index>(i)) = rest_normals.row(mine[i].first).transpose();
    const std::vector<Eigen::Index> first = near_repeats(normals, kPieceMergeTolerance);
    std::vector<size_t> place(mine.size());  // of a kept piece, in the merged list
    size_t kept = 0;
    for (size_t i = 0; i < mine.size(); ++i) {
      if (first[i] == static_cast<Eigen::Index>(i)) {
        place[i] = kept;
        mine[kept++] = mine[i];
      } else {
        mine[place[static_cast<size_t>(first[i])]].second += mine[i].second;
      }
    }
    mine.resize(kept);
  });
  return pieces;
}

void LocalStep::set_rest(const TetMesh& rest) {
  T = &rest.T;
  rest_inverse.resize(static_cast<size_t>(rest.T.rows()));
  for (Eigen::Index t = 0; t < rest.T.rows(); ++t) rest_inverse[static_cast<size_t>(t)] = edge_matrix(rest.V, rest.T.row(t)).inverse();
}

LocalStepState LocalStep::make_state() const {
  const size_t nt = rest_inverse.size();
  LocalStepState s;
  s.L.assign(nt, Eigen::Matrix3d::Identity());
  s.extra.resize(nt);
  s.risky_area.resize(nt);
  s.ae_area.resize(nt);
  return s;
}

void LocalStep::run(const Points& V, LocalStepState& s) const {
  parallel_for(static_cast<int>(rest_inverse.size()), [&](int t) {
    const size_t ts = static_cast<size_t>(t);
    const Eigen::Matrix3d M = closest_rotation(edge_matrix(V, T->row(t)) * rest_inverse[ts]);
    s.L[ts] = M;
    s.ae_area[ts] = s.risky_area[ts] = 0.0;
    const auto& pc = pieces[ts];
    if (pc.empty() || skip[ts]) return;
    // Most surface tets are safe: look before building the patch.
    for (const auto& [face, area] : pc)
      if ((M * rest_normals.row(face).transpose()).dot(d) + tau < 0) s.risky_area[ts] += area;
    if (!(s.risky_area[ts] > 0.0)) return;
    s.extra[ts].setIdentity();
    Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(pc.size()));
    Eigen::VectorXd areas(static_cast<Eigen::Index>(pc.size()));
    for (size_t i = 0; i < pc.size(); ++i) {
      normals.col(static_cast<Eigen::Index>(i)) = M * rest_normals.row(pc[i].first).transpose();
      areas(static_cast<Eigen::Index>(i)) = pc[i].second;
    }
    MinRotationOptions mo;
    mo.tie_break = tie[ts];
    const ProxyRotation pr = proxy_rotation(normals, areas, d, tau, mo, proxies);
    s.ae_area[ts] = pr.approximation_error * areas.sum();
    const bool minimal_found = !pr.undefined && pr.solution.feasible;
    if (edge_axis[ts].squaredNorm() > 0.0) {
      const MinRotation edge = min_rotation_about_axis(normals, d, tau, edge_axis[ts]);
      if (edge.feasible && (!minimal_found || edge.angle <= pr.solution.angle + edge_slack)) {
        s.extra[ts] = Eigen::AngleAxisd(std::min(edge.angle, max_step), edge_axis[ts]).toRotationMatrix();
        return;
      }
    }
    if (!minimal_found) return;
    s.extra[ts] = Eigen::AngleAxisd(std::min(pr.solution.angle, max_step), pr.solution.axis).toRotationMatrix();
  });
}

}  // namespace slim
