// The minimal rotation of one patch, exact when possible and on K-means proxies otherwise
// (paper §III-A and §III-C), with the approximation error of §IV-C.
//
//   ProxyRotation proxy_rotation(normals, areas, d, tau [, rotation_options, proxy_options])
//
// Inputs
//   normals  3 by n unit face normals (exact zero column: zero-area face).
//   areas    n face areas, mesh units² (finite, >= 0). Faces with area 0 or a zero normal take
//            no part anywhere: they constrain nothing and count for nothing in AE.
//   d, tau   unit print direction and sin(alpha_max), tau in [0, 1), as for min_rotation.
//   rotation_options  passed to every min_rotation call (the tie-break for straight-down faces).
//   proxy_options     see ProxyOptions.
// Output (ProxyRotation)
//   solution   the min_rotation result to apply: exact on all faces (k = 0), else on k proxies.
//   k          0: exact, every face is its own proxy; 1..max_k: proxies used.
//   undefined  the area-weighted normals cancel out (a closed blob in one tet): not even one
//              proxy exists. solution is then the identity with feasible = false: not moved.
//   approximation_error  AE in [0, 1]: the share of area whose normal is more than ae_threshold
//              from its proxy. 0 when exact; 1 when undefined (no face is represented).
//   proxies    3 by k unit proxy normals (3 by 0 when exact or undefined).
// Throws std::invalid_argument for the inputs min_rotation or gauss_kmeans reject, mismatched
// sizes, max_k < 1 or ae_threshold outside [0, pi].
//
// The search, as in the paper: solve on all faces; if that region is empty, raise k = 1, 2, ...
// and solve on the k K-means proxies until the proxies' region is empty too or k = max_k.
// One proxy is always feasible (rotate it up), so the search ends with some k >= 1 unless the
// single proxy is undefined. Among the feasible k the lowest AE wins, ties to the larger k: in
// practice that is the last feasible k the paper keeps, and it guarantees that raising k never
// makes AE worse than k = 1. k stops rising early when K-means finds no more distinct directions,
// or when a proxy comes out undefined.
//
// AE. The paper calls a face well approximated when n·c <= cos(alpha_max): read literally that
// praises faces far from their proxy, and at its own alpha_max = 0 it holds for every face (and
// the reversed n·c >= 1 for almost none). So AE uses a fixed threshold: a face is well
// approximated when angle(n, proxy) <= ae_threshold.
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Core>

#include "core/rotation/min_rotation.h"

namespace slim {

struct ProxyOptions {
  int max_k = 8;  // most proxies tried; each proxy adds a constraint, so large k is rarely feasible
  // 15°: the step slicers offer for the overhang threshold, so a face within it of its proxy
  // counts as overhanging or not much like the proxy does. Independent of alpha_max (see above).
  double ae_threshold = 15.0 * M_PI / 180.0;  // radians, in [0, pi]
  std::uint32_t seed = 1;                     // K-means++ seed (std::mt19937): same seed, same result
  int kmeans_max_iterations = 100;            // the paper's cap (§III-C)
};

struct ProxyRotation {
  MinRotation solution;
  int k = 0;
  bool undefined = false;
  double approximation_error = 0.0;
  Eigen::Matrix3Xd proxies = Eigen::Matrix3Xd(3, 0);
  bool exact() const { return k == 0 && !undefined; }
};

ProxyRotation proxy_rotation(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas,
                             const Eigen::Vector3d& d, double tau,
                             const MinRotationOptions& rotation_options = {},
                             const ProxyOptions& proxy_options = {});

// AE of a clustering: the share of the total area of faces with assignment >= 0 whose normal is
// more than threshold radians from centroids.col(assignment(i)); 0 when that area is 0.
// normals 3 by n, areas n, centroids 3 by k, assignment n (-1 = not counted).
double approximation_error(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas,
                           const Eigen::Matrix3Xd& centroids, const Eigen::VectorXi& assignment,
                           double threshold);

}  // namespace slim
