// The rotation nearest a 3x3 matrix: the "M" of the paper's local step (§II), M = U W^T from
// Q = U S W^T, with the reflection case taken care of.
//
//   M = closest_rotation(Q);
//
// Inputs:
//   Q  3 by 3, any real matrix. In the local step Q = V_t^cur (V_t^0)^-1 of one tet (unitless).
// Output:
//   M  3 by 3 rotation (M^T M = I, det M = +1) minimising ||M - Q||_F, equivalently maximising
//      trace(M^T Q); the maximum is s1 + s2 + sign(det Q) s3 for the singular values s1>=s2>=s3.
//      - det Q > 0: M is the orthogonal polar factor of Q (Q = M P, P symmetric positive definite).
//      - det Q < 0 (an inverted tet): the polar factor is a reflection; M flips the singular
//        vector of the smallest singular value instead (U diag(1, 1, -1) W^T).
//      - Where the minimiser is not unique (rank <= 1, or det Q < 0 with s2 == s3) M is one of the
//        minimisers, the same one on every run.
//      - Non-finite Q: a matrix of NaN. It never throws, because the local step calls it inside
//        OpenMP loops, where an escaping exception terminates the host program (MeshLab).
//
// Why two methods: Eigen's JacobiSVD of every tet's 3x3 matrix is a large share of an iteration on
// a large domain. For the usual input (det Q > 0, well conditioned, often already close to a
// rotation) Higham's scaled Newton iteration X <- (z X + X^-T / z) / 2, with 3x3 inverses by cross
// products, reaches machine precision in 3-8 steps and is several times faster.
// Inputs with det Q <= 0 or a condition number above 1e6, and the rare iteration that has not
// converged after 20 steps, go to the SVD. The result is deterministic: it depends on Q only.
#pragma once

#include <Eigen/Core>

namespace slim {

Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& Q);

// The same answer through Eigen's JacobiSVD alone: the fallback above, and the reference the
// tests and the benchmark compare against. Several times slower than closest_rotation.
Eigen::Matrix3d closest_rotation_svd(const Eigen::Matrix3d& Q);

}  // namespace slim
