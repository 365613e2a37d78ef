// slim::proxy_rotation: exact when it can be, K-means proxies when it cannot, the AE measure,
// and the closed blob whose single proxy is undefined.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/geometry/surface.h"
#include "core/rotation/gauss_kmeans.h"
#include "core/rotation/proxy_rotation.h"
#include "support/min_rotation_reference.h"
#include "support/shapes.h"

using namespace slim;

namespace {

const double kDeg = M_PI / 180.0;
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

struct Patch {
  Eigen::Matrix3Xd normals;
  Eigen::VectorXd areas;
};

// n faces within `spread` of a downward direction, random areas.
Patch risky_patch(std::mt19937& rng, int n, double spread) {
  std::uniform_real_distribution<double> area(0.1, 2.0);
  Patch p{test::random_normals_in_cap(rng, n, test::random_in_cap(rng, -kUp, 30 * kDeg), spread), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) p.areas(i) = area(rng);
  return p;
}

void expect_finite(const ProxyRotation& r) {
  EXPECT_TRUE(r.solution.rotation.allFinite() && r.solution.closest.allFinite() && r.solution.axis.allFinite());
  EXPECT_TRUE(std::isfinite(r.solution.angle) && std::isfinite(r.approximation_error));
  EXPECT_TRUE(r.proxies.allFinite());
}

}  // namespace

TEST(ProxyRotation, ExactWhenTheFacesAllowIt) {
  std::mt19937 rng(1);
  for (int k = 0; k < 20; ++k) {
    const Patch p = risky_patch(rng, 30, 40 * kDeg);
    const double tau = std::sin(45 * kDeg);
    const ProxyRotation r = proxy_rotation(p.normals, p.areas, kUp, tau);
    const MinRotation exact = min_rotation(p.normals, kUp, tau);
    ASSERT_TRUE(exact.feasible);
    EXPECT_TRUE(r.exact());
    EXPECT_EQ(r.k, 0);
    EXPECT_EQ(r.approximation_error, 0.0);
    EXPECT_EQ(r.proxies.cols(), 0);
    EXPECT_EQ(r.solution.rotation, exact.rotation);
  }
}

TEST(ProxyRotation, InfeasiblePatchesUseProxiesAndNeverDoWorseThanOne) {
  std::mt19937 rng(2);
  int proxies_beyond_one = 0;
  for (int k = 0; k < 40; ++k) {
    const Patch p = risky_patch(rng, 60, 150 * kDeg);  // wraps most of the sphere
    const double tau = std::sin(15 * kDeg);
    if (min_rotation(p.normals, kUp, tau).feasible) continue;
    ProxyOptions options;
    options.seed = 7;
    const ProxyRotation r = proxy_rotation(p.normals, p.areas, kUp, tau, {}, options);
    SCOPED_TRACE("patch " + std::to_string(k));
    expect_finite(r);
    ASSERT_FALSE(r.undefined);
    EXPECT_FALSE(r.exact());
    EXPECT_GE(r.k, 1);
    EXPECT_LE(r.k, options.max_k);
    EXPECT_EQ(r.proxies.cols(), r.k);
    ASSERT_TRUE(r.solution.feasible);
    // The rotation makes every proxy safe.
    for (Eigen::Index c = 0; c < r.proxies.cols(); ++c)
      EXPECT_GE((r.solution.rotation * r.proxies.col(c)).dot(kUp), -tau - 1e-9);
    // AE at the chosen k is no larger than with a single proxy.
    GaussKmeansOptions kmeans;
    kmeans.seed = options.seed;
    const GaussKmeans one = gauss_kmeans(p.normals, p.areas, 1, kmeans);
    const double ae_one = approximation_error(p.normals, p.areas, one.centroids, one.assignment, options.ae_threshold);
    EXPECT_LE(r.approximation_error, ae_one);
    EXPECT_GE(r.approximation_error, 0.0);
    EXPECT_LE(r.approximation_error, 1.0);
    proxies_beyond_one += r.k > 1;
  }
  EXPECT_GT(proxies_beyond_one, 5);  // k really is raised
}

TEST(ProxyRotation, RepeatsExactly) {
  std::mt19937 rng(3);
  const Patch p = risky_patch(rng, 80, 150 * kDeg);
  const ProxyRotation a = proxy_rotation(p.normals, p.areas, kUp, 0.2), b = proxy_rotation(p.normals, p.areas, kUp, 0.2);
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.proxies, b.proxies);
  EXPECT_EQ(a.solution.rotation, b.solution.rotation);
  EXPECT_EQ(a.approximation_error, b.approximation_error);
}

TEST(ProxyRotation, MaxKIsRespected) {
  std::mt19937 rng(4);
  const Patch p = risky_patch(rng, 80, 150 * kDeg);
  ProxyOptions options;
  options.max_k = 1;
  const ProxyRotation r = proxy_rotation(p.normals, p.areas, kUp, 0.1, {}, options);
  ASSERT_FALSE(min_rotation(p.normals, kUp, 0.1).feasible);
  EXPECT_EQ(r.k, 1);
  EXPECT_TRUE(r.solution.feasible);
}

TEST(ProxyRotation, ClosedBlobIsLeftAloneWithoutNaN) {
  const Surface blob = test::icosphere(2);
  const ProxyRotation r = proxy_rotation(face_normals(blob).transpose(), face_areas(blob), kUp, std::sin(45 * kDeg));
  expect_finite(r);
  EXPECT_TRUE(r.undefined);
  EXPECT_FALSE(r.exact());
  EXPECT_FALSE(r.solution.feasible);
  EXPECT_EQ(r.solution.rotation, Eigen::Matrix3d::Identity());
  EXPECT_EQ(r.solution.angle, 0.0);
  EXPECT_EQ(r.approximation_error, 1.0);
}

TEST(ProxyRotation, ZeroAreaFacesTakeNoPart) {
  std::mt19937 rng(5);
  const Patch p = risky_patch(rng, 20, 150 * kDeg);
  Patch padded = p;
  padded.normals.conservativeResize(3, 22);
  padded.areas.conservativeResize(22);
  padded.normals.col(20) = Eigen::Vector3d::Zero();  // a degenerate face
  padded.areas(20) = 0.0;
  padded.normals.col(21) = -kUp;  // a direction, but no area
  padded.areas(21) = 0.0;
  const ProxyRotation a = proxy_rotation(p.normals, p.areas, kUp, 0.3), b = proxy_rotation(padded.normals, padded.areas, kUp, 0.3);
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.solution.rotation, b.solution.rotation);
  EXPECT_EQ(a.approximation_error, b.approximation_error);
}

TEST(ApproximationError, IsTheAreaShareBeyondTheThreshold) {
  const Eigen::Vector3d proxy = -kUp;
  Eigen::Matrix3Xd n(3, 3);
  n << test::axis_angle(Eigen::Vector3d::UnitX(), 10 * kDeg) * proxy, test::axis_angle(Eigen::Vector3d::UnitY(), 20 * kDeg) * proxy,
      test::axis_angle(Eigen::Vector3d::UnitX(), 15 * kDeg) * proxy;
  const Eigen::Vector3d areas(1.0, 3.0, 2.0);
  const Eigen::Matrix3Xd centroids = proxy;
  const Eigen::Vector3i assignment(0, 0, 0);
  EXPECT_NEAR(approximation_error(n, areas, centroids, assignment, 15 * kDeg + 1e-12), 3.0 / 6.0, 1e-15);  // 15° is still good
  EXPECT_NEAR(approximation_error(n, areas, centroids, assignment, 5 * kDeg), 1.0, 1e-15);
  EXPECT_NEAR(approximation_error(n, areas, centroids, assignment, 25 * kDeg), 0.0, 1e-15);
  EXPECT_EQ(approximation_error(n, areas, centroids, Eigen::Vector3i(-1, -1, -1), 0.1), 0.0);  // nothing counted
}

TEST(ProxyRotation, RejectsBadInput) {
  std::mt19937 rng(6);
  const Patch p = risky_patch(rng, 5, 40 * kDeg);
  EXPECT_THROW(proxy_rotation(p.normals, Eigen::VectorXd::Ones(4), kUp, 0.5), std::invalid_argument);
  Eigen::VectorXd areas = p.areas;
  areas(0) = -1;
  EXPECT_THROW(proxy_rotation(p.normals, areas, kUp, 0.5), std::invalid_argument);
  ProxyOptions options;
  options.max_k = 0;
  EXPECT_THROW(proxy_rotation(p.normals, p.areas, kUp, 0.5, {}, options), std::invalid_argument);
  options = {};
  options.ae_threshold = -0.1;
  EXPECT_THROW(proxy_rotation(p.normals, p.areas, kUp, 0.5, {}, options), std::invalid_argument);
  Eigen::Matrix3Xd n = p.normals;
  n(1, 2) = std::nan("");
  EXPECT_THROW(proxy_rotation(n, p.areas, kUp, 0.5), std::invalid_argument);
  EXPECT_THROW(proxy_rotation(p.normals, p.areas, kUp, 1.5), std::invalid_argument);
}
