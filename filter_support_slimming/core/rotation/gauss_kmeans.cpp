#include "core/rotation/gauss_kmeans.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "core/rotation/min_rotation.h"

namespace slim {

namespace {

// A weighted normal sum shorter than this share of the cluster's weight has no direction: the
// members cancel out (a closed blob), and renormalising would amplify rounding into a random proxy.
constexpr double kZeroSumShare = 1e-9;

// Uniform double in [0, 1) from 53 random bits; the same on every standard library.
double unit_uniform(std::mt19937& rng) {
  const std::uint64_t high = rng() >> 5, low = rng() >> 6;  // 27 + 26 bits
  return static_cast<double>((high << 26) | low) * (1.0 / 9007199254740992.0);  // 2^-53
}

double geodesic(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));  // arccos(a·b), accurate near 0 and pi
}

void check_inputs(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& weights, int k,
                  const GaussKmeansOptions& options) {
  check_face_normals_and_areas(normals, weights, "gauss_kmeans");
  if (k < 1) throw std::invalid_argument("gauss_kmeans: k must be >= 1, got " + std::to_string(k));
  if (options.max_iterations < 1)
    throw std::invalid_argument("gauss_kmeans: max_iterations must be >= 1");
  if (!(options.tolerance >= 0.0)) throw std::invalid_argument("gauss_kmeans: tolerance must be >= 0");
}

// Index drawn with probability ∝ mass(i); -1 when all mass is zero.
Eigen::Index draw(const Eigen::VectorXd& mass, std::mt19937& rng) {
  const double total = mass.sum();
  if (!(total > 0.0)) return -1;
  const double target = unit_uniform(rng) * total;
  double running = 0.0;
  Eigen::Index last_positive = -1;
  for (Eigen::Index i = 0; i < mass.size(); ++i) {
    if (mass(i) <= 0.0) continue;
    running += mass(i);
    last_positive = i;
    if (target < running) return i;
  }
  return last_positive;  // rounding left target at the very end
}

// Weighted k-means++: returns up to k seed normals (fewer when every face sits on a seed).
Eigen::Matrix3Xd seed_centroids(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& weights,
                                const std::vector<bool>& used, int k, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(normals.cols());  // weight · D² to the nearest seed
  for (Eigen::Index i = 0; i < normals.cols(); ++i)
    if (used[static_cast<size_t>(i)]) mass(i) = weights(i);
  Eigen::Matrix3Xd seeds(3, k);
  int count = 0;
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(normals.cols(), M_PI);
  while (count < k) {
    const Eigen::Index pick = draw(mass, rng);
    if (pick < 0) break;
    seeds.col(count++) = normals.col(pick);
    for (Eigen::Index i = 0; i < normals.cols(); ++i) {
      if (!used[static_cast<size_t>(i)]) continue;
      nearest(i) = std::min(nearest(i), geodesic(normals.col(i), normals.col(pick)));
      mass(i) = weights(i) * nearest(i) * nearest(i);
    }
  }
  return seeds.leftCols(count);
}

}  // namespace

void check_face_normals_and_areas(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas, const char* caller) {
  if (areas.size() != normals.cols())
    throw std::invalid_argument(std::string(caller) + ": " + std::to_string(normals.cols()) + " normals but " +
                                std::to_string(areas.size()) + " areas");
  for (Eigen::Index i = 0; i < areas.size(); ++i)
    if (!(areas(i) >= 0.0) || !std::isfinite(areas(i)))
      throw std::invalid_argument(std::string(caller) + ": area " + std::to_string(i) + " must be finite and >= 0");
  check_face_normals(normals, caller);
}

GaussKmeans gauss_kmeans(const Eigen::Matrix3Xd& normals_in, const Eigen::VectorXd& weights, int k,
                         const GaussKmeansOptions& options) {
  check_inputs(normals_in, weights, k, options);
  const Eigen::Index n = normals_in.cols();
  Eigen::Matrix3Xd normals = normals_in;
  std::vector<bool> used(static_cast<size_t>(n), false);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double length = normals.col(i).norm();
    if (length > 0.0 && weights(i) > 0.0) {
      normals.col(i) /= length;
      used[static_cast<size_t>(i)] = true;
    }
  }

  GaussKmeans r;
  r.centroids = seed_centroids(normals, weights, used, k, options.seed);
  const Eigen::Index clusters = r.centroids.cols();
  r.assignment = Eigen::VectorXi::Constant(n, -1);
  r.cluster_weight = Eigen::VectorXd::Zero(clusters);
  r.defined.assign(static_cast<size_t>(clusters), true);
  if (clusters == 0) {
    r.converged = true;
    return r;
  }

  for (r.iterations = 1; r.iterations <= options.max_iterations; ++r.iterations) {
    bool reassigned = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!used[static_cast<size_t>(i)]) continue;
      int best = 0;  // the largest n·c; the first one on ties
      double best_closeness = r.centroids.col(0).dot(normals.col(i));
      for (Eigen::Index c = 1; c < clusters; ++c) {
        const double closeness = r.centroids.col(c).dot(normals.col(i));
        if (closeness > best_closeness) best = static_cast<int>(c), best_closeness = closeness;
      }
      if (r.assignment(i) != best) reassigned = true;
      r.assignment(i) = best;
    }

    Eigen::Matrix3Xd sums = Eigen::Matrix3Xd::Zero(3, clusters);
    r.cluster_weight.setZero();
    for (Eigen::Index i = 0; i < n; ++i) {
      if (r.assignment(i) < 0) continue;
      sums.col(r.assignment(i)) += weights(i) * normals.col(i);
      r.cluster_weight(r.assignment(i)) += weights(i);
    }
    double moved = 0.0;
    for (Eigen::Index c = 0; c < clusters; ++c) {
      const double length = sums.col(c).norm();
      if (r.cluster_weight(c) == 0.0) continue;  // empty: keep the centroid, it may win members back
      r.defined[static_cast<size_t>(c)] = length > kZeroSumShare * r.cluster_weight(c);
      if (!r.defined[static_cast<size_t>(c)]) continue;  // no direction: keep the previous centroid
      const Eigen::Vector3d updated = sums.col(c) / length;
      moved = std::max(moved, geodesic(updated, r.centroids.col(c)));
      r.centroids.col(c) = updated;
    }
    if (!reassigned || moved <= options.tolerance) {
      r.converged = true;
      break;
    }
  }
  r.iterations = std::min(r.iterations, options.max_iterations);
  return r;
}

}  // namespace slim
