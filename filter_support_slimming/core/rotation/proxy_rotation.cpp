#include "core/rotation/proxy_rotation.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/rotation/gauss_kmeans.h"

namespace slim {

namespace {

void check_inputs(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas, const ProxyOptions& options) {
  check_face_normals_and_areas(normals, areas, "proxy_rotation");  // before zero-area faces are dropped
  if (options.max_k < 1) throw std::invalid_argument("proxy_rotation: max_k must be >= 1");
  if (!(options.ae_threshold >= 0.0 && options.ae_threshold <= M_PI))
    throw std::invalid_argument("proxy_rotation: ae_threshold must be an angle in [0, pi] radians");
}

// The faces that take part: a direction and some area.
void participating_faces(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas,
                         Eigen::Matrix3Xd& kept_normals, Eigen::VectorXd& kept_areas) {
  kept_normals.resize(3, normals.cols());
  kept_areas.resize(normals.cols());
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (areas(i) > 0.0 && normals.col(i).squaredNorm() > 0.0) {
      kept_normals.col(count) = normals.col(i);
      kept_areas(count++) = areas(i);
    }
  }
  kept_normals.conservativeResize(3, count);
  kept_areas.conservativeResize(count);
}

}  // namespace

double approximation_error(const Eigen::Matrix3Xd& normals, const Eigen::VectorXd& areas,
                           const Eigen::Matrix3Xd& centroids, const Eigen::VectorXi& assignment,
                           double threshold) {
  double total = 0.0, badly_approximated = 0.0;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (assignment(i) < 0) continue;
    const Eigen::Vector3d n = normals.col(i), c = centroids.col(assignment(i));
    const double angle = std::atan2(n.cross(c).norm(), n.dot(c));  // arccos(n·c) for unit n, c
    total += areas(i);
    if (angle > threshold) badly_approximated += areas(i);
  }
  return total > 0.0 ? badly_approximated / total : 0.0;
}

ProxyRotation proxy_rotation(const Eigen::Matrix3Xd& normals_in, const Eigen::VectorXd& areas_in,
                             const Eigen::Vector3d& d, double tau, const MinRotationOptions& rotation_options,
                             const ProxyOptions& proxy_options) {
  check_inputs(normals_in, areas_in, proxy_options);
  Eigen::Matrix3Xd normals;
  Eigen::VectorXd areas;
  participating_faces(normals_in, areas_in, normals, areas);

  ProxyRotation result;
  result.solution = min_rotation(normals, d, tau, rotation_options);  // also checks normals, d, tau
  if (result.solution.feasible) return result;                        // exact: k = 0, AE = 0

  GaussKmeansOptions kmeans_options;
  kmeans_options.max_iterations = proxy_options.kmeans_max_iterations;
  kmeans_options.seed = proxy_options.seed;
  bool found = false;
  Eigen::Index previous_proxy_count = 0;
  for (int k = 1; k <= proxy_options.max_k; ++k) {
    const GaussKmeans clusters = gauss_kmeans(normals, areas, k, kmeans_options);
    Eigen::Matrix3Xd proxies(3, clusters.centroids.cols());
    Eigen::Index proxy_count = 0;
    bool undefined = false;
    for (Eigen::Index c = 0; c < clusters.centroids.cols(); ++c) {
      if (clusters.cluster_weight(c) == 0.0) continue;  // empty: stands for no face
      undefined = undefined || !clusters.defined[static_cast<size_t>(c)];
      proxies.col(proxy_count++) = clusters.centroids.col(c);
    }
    proxies.conservativeResize(3, proxy_count);
    if (undefined) {
      if (k > 1) break;  // keep the best k found so far
      // Not even one proxy: leave the patch where it is, and say so.
      result.undefined = true;
      result.solution = min_rotation(Eigen::Matrix3Xd(3, 0), d, tau, rotation_options);  // identity
      result.solution.feasible = false;
      result.approximation_error = 1.0;
      return result;
    }
    if (proxy_count <= previous_proxy_count) break;  // no new direction: larger k adds nothing
    previous_proxy_count = proxy_count;

    const MinRotation solution = min_rotation(proxies, d, tau, rotation_options);
    if (!solution.feasible) break;
    const double error = approximation_error(normals, areas, clusters.centroids, clusters.assignment,
                                             proxy_options.ae_threshold);
    if (!found || error <= result.approximation_error) {
      found = true;
      result.solution = solution;
      result.k = k;
      result.approximation_error = error;
      result.proxies = proxies;
    }
  }
  return result;
}

}  // namespace slim
