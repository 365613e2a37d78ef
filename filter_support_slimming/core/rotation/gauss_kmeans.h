// Area-weighted spherical K-means of face normals on the Gauss sphere (paper §III-C): the proxies
// the minimal rotation is solved on when the exact region is empty.
//
//   GaussKmeans gauss_kmeans(normals, weights, k [, options])
//
// Inputs
//   normals  3 by n unit face normals. An exact zero column (zero-area face) is ignored.
//   weights  n face areas (mesh units², finite, >= 0). A face of weight 0 is ignored too: it
//            neither seeds nor pulls a centroid, so it cannot change the proxies.
//   k        clusters wanted, >= 1.
// Output (GaussKmeans)
//   centroids       3 by k' unit proxies, k' <= k: fewer when the faces have fewer than k
//                   distinct directions (seeding stops when every face coincides with a seed).
//   assignment      n cluster indices into centroids; -1 for ignored faces.
//   cluster_weight  k' summed weights of the members (0 for a cluster that ended empty).
//   defined         k' flags: false when the cluster's weighted normal sum is (nearly) zero, so it
//                   has no direction (a closed blob in one cluster). Its centroid is then kept
//                   from the previous iteration (at first: its seed, a member normal), never NaN.
//   iterations      update rounds run; converged: stopped because nothing moved any more.
// Throws std::invalid_argument for mismatched sizes, negative or non-finite weights, non-finite
// or non-unit normals (|‖n‖ - 1| > 1e-6), k < 1, or bad options.
//
// The algorithm, and why:
//  * Seeding is weighted k-means++: the first seed is drawn with probability ∝ area, each next
//    one ∝ area · (geodesic distance to the nearest seed)². It spreads the seeds over the
//    directions that carry area. The draws come from std::mt19937 with a fixed seed (turned into
//    doubles here, not by std::uniform_real_distribution, whose output differs between standard
//    libraries), so every run repeats exactly.
//  * Distances are geodesic, arccos(n·c). Assigning to the nearest centroid only needs the
//    largest n·c, since arccos is decreasing; ties go to the lower cluster index.
//  * A centroid is the area-weighted mean of its members renormalised (Eq. 5): the cheap stand-in
//    for the geodesic mean. An empty cluster keeps its previous centroid, and may win members
//    back in the next round.
//  * Stops after max_iterations (the paper uses 100), or when no centroid moved more than
//    tolerance radians, or when no assignment changed.
// Cost O(k n) per iteration.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace slim {

struct GaussKmeansOptions {
  int max_iterations = 100;  // the paper's cap (§III-C)
  double tolerance = 1e-12;  // radians; a round in which no centroid moves more than this ends it
  std::uint32_t seed = 1;    // std::mt19937 seed for the k-means++ draws; same seed, same result
};

struct GaussKmeans {
  Eigen::Matrix3Xd centroids;      // 3 by k', unit
  Eigen::VectorXi assignment;      // n, index into centroids or -1
  Eigen::VectorXd cluster_weight;  // k'
  std::vector<bool> defined;       // k'
  int iterations = 0;
  bool converged = false;
};

GaussKmeans gauss_kmeans(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& weights, int k,
                         const GaussKmeansOptions& options = {});

// Throws std::invalid_argument, naming `caller`, unless the 3 by n `normals` pass
// check_face_normals (min_rotation.h) and `areas` holds n finite values >= 0.
void check_face_normals_and_areas(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas, const char* caller);

}  // namespace slim
