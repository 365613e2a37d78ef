// slim::gauss_kmeans: repeatability, recovery of separated clusters, the area-weighted centroid,
// and the degenerate cases (more clusters than directions, cancelling normals, ignored faces).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>

#include "core/geometry/surface.h"
#include "core/rotation/gauss_kmeans.h"
#include "support/min_rotation_reference.h"
#include "support/shapes.h"

using namespace slim;

namespace {

const double kDeg = M_PI / 180.0;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

struct Patch {
  Eigen::Matrix3Xd normals;
  Eigen::VectorXd areas;
};

// `per_group` normals within `spread` of each centre, random areas in [0.1, 2].
Patch groups_around(const Eigen::Matrix3Xd& centres, int per_group, double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> area(0.1, 2.0);
  Patch p;
  p.normals.resize(3, centres.cols() * per_group);
  p.areas.resize(centres.cols() * per_group);
  for (Eigen::Index i = 0; i < p.normals.cols(); ++i) {
    p.normals.col(i) = test::random_in_cap(rng, centres.col(i % centres.cols()), spread);
    p.areas(i) = area(rng);
  }
  return p;
}

Patch closed_blob() {
  const Surface s = test::icosphere(2);
  return {face_normals(s).transpose(), face_areas(s)};
}

void expect_unit_and_finite(const GaussKmeans& r) {
  ASSERT_TRUE(r.centroids.allFinite());
  for (Eigen::Index c = 0; c < r.centroids.cols(); ++c) EXPECT_NEAR(r.centroids.col(c).norm(), 1.0, 1e-12);
  EXPECT_TRUE(r.cluster_weight.allFinite());
}

}  // namespace

TEST(GaussKmeans, RepeatsExactly) {
  std::mt19937 rng(1);
  const Patch p = groups_around(test::random_normals_in_cap(rng, 4, Eigen::Vector3d::UnitZ(), M_PI), 30, 30 * kDeg, 2);
  for (int k = 1; k <= 6; ++k) {
    const GaussKmeans a = gauss_kmeans(p.normals, p.areas, k), b = gauss_kmeans(p.normals, p.areas, k);
    EXPECT_EQ(a.centroids, b.centroids);
    EXPECT_EQ(a.assignment, b.assignment);
    EXPECT_EQ(a.iterations, b.iterations);
  }
}

TEST(GaussKmeans, RecoversWellSeparatedClusters) {
  const Eigen::Matrix3Xd centres = Eigen::Matrix3d::Identity();  // three directions 90° apart
  const Patch p = groups_around(centres, 40, 5 * kDeg, 3);
  for (std::uint32_t seed : {1u, 2u, 3u, 99u}) {
    GaussKmeansOptions options;
    options.seed = seed;
    const GaussKmeans r = gauss_kmeans(p.normals, p.areas, 3, options);
    expect_unit_and_finite(r);
    ASSERT_EQ(r.centroids.cols(), 3);
    EXPECT_TRUE(r.converged);
    std::set<int> labels;
    for (int g = 0; g < 3; ++g) {
      const int label = r.assignment(g);  // face g belongs to group g
      labels.insert(label);
      EXPECT_LT(angle_between(r.centroids.col(label), centres.col(g)), 3 * kDeg);
      for (Eigen::Index i = g; i < p.normals.cols(); i += 3) EXPECT_EQ(r.assignment(i), label);
    }
    EXPECT_EQ(labels.size(), 3u);
  }
}

TEST(GaussKmeans, CentroidIsTheAreaWeightedMeanRenormalised) {
  Eigen::Matrix3Xd n(3, 2);
  n << Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0);
  const Eigen::Vector2d areas(3.0, 1.0);
  const GaussKmeans r = gauss_kmeans(n, areas, 1);
  EXPECT_LT((r.centroids.col(0) - Eigen::Vector3d(3, 1, 0).normalized()).norm(), 1e-15);
  EXPECT_NEAR(r.cluster_weight(0), 4.0, 1e-15);
  EXPECT_TRUE(r.defined[0]);
}

TEST(GaussKmeans, EveryFaceEndsAtItsNearestCentroid) {
  std::mt19937 rng(4);
  const Patch p = groups_around(test::random_normals_in_cap(rng, 5, Eigen::Vector3d::UnitZ(), M_PI), 20, 40 * kDeg, 5);
  for (int k = 2; k <= 8; ++k) {
    const GaussKmeans r = gauss_kmeans(p.normals, p.areas, k);
    expect_unit_and_finite(r);
    if (!r.converged) continue;
    for (Eigen::Index i = 0; i < p.normals.cols(); ++i) {
      const Eigen::VectorXd closeness = r.centroids.transpose() * p.normals.col(i);
      EXPECT_GE(closeness(r.assignment(i)), closeness.maxCoeff() - 1e-15);
    }
  }
}

TEST(GaussKmeans, MoreClustersThanDirections) {
  Eigen::Matrix3Xd n(3, 6);
  n << Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitZ(),
      -Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ();
  const GaussKmeans r = gauss_kmeans(n, Eigen::VectorXd::Ones(6), 5);
  expect_unit_and_finite(r);
  EXPECT_EQ(r.centroids.cols(), 2);  // seeding stops once every face sits on a seed
  EXPECT_NE(r.assignment(0), r.assignment(3));
}

TEST(GaussKmeans, CancellingNormalsGiveAnUndefinedButFiniteCentroid) {
  const Patch blob = closed_blob();
  const GaussKmeans r = gauss_kmeans(blob.normals, blob.areas, 1);
  expect_unit_and_finite(r);
  EXPECT_FALSE(r.defined[0]);  // the area-weighted normals of a closed surface sum to zero
  Eigen::Matrix3Xd pair(3, 2);
  pair << Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY();
  const GaussKmeans q = gauss_kmeans(pair, Eigen::Vector2d(1.0, 1.0), 1);
  expect_unit_and_finite(q);
  EXPECT_FALSE(q.defined[0]);
}

TEST(GaussKmeans, ZeroNormalsAndZeroAreasAreIgnored) {
  const Patch p = groups_around(Eigen::Matrix3d::Identity(), 10, 10 * kDeg, 6);
  Patch padded = p;
  padded.normals.conservativeResize(3, p.normals.cols() + 2);
  padded.areas.conservativeResize(p.areas.size() + 2);
  padded.normals.col(p.normals.cols()) = Eigen::Vector3d::Zero();
  padded.areas(p.areas.size()) = 0.0;
  padded.normals.col(p.normals.cols() + 1) = -Eigen::Vector3d::UnitX();  // a direction, but no area
  padded.areas(p.areas.size() + 1) = 0.0;
  const GaussKmeans a = gauss_kmeans(p.normals, p.areas, 3), b = gauss_kmeans(padded.normals, padded.areas, 3);
  EXPECT_EQ(a.centroids, b.centroids);
  EXPECT_EQ(b.assignment(p.normals.cols()), -1);
  EXPECT_EQ(b.assignment(p.normals.cols() + 1), -1);
  const GaussKmeans none = gauss_kmeans(Eigen::Matrix3Xd::Zero(3, 3), Eigen::VectorXd::Ones(3), 2);
  EXPECT_EQ(none.centroids.cols(), 0);
}

TEST(GaussKmeans, RejectsBadInput) {
  const Patch p = groups_around(Eigen::Matrix3d::Identity(), 2, 0.1, 7);
  EXPECT_THROW(gauss_kmeans(p.normals, Eigen::VectorXd::Ones(5), 2), std::invalid_argument);
  Eigen::VectorXd areas = p.areas;
  areas(1) = -1.0;
  EXPECT_THROW(gauss_kmeans(p.normals, areas, 2), std::invalid_argument);
  areas(1) = std::nan("");
  EXPECT_THROW(gauss_kmeans(p.normals, areas, 2), std::invalid_argument);
  EXPECT_THROW(gauss_kmeans(p.normals, p.areas, 0), std::invalid_argument);
  Eigen::Matrix3Xd n = p.normals;
  n(0, 0) *= 1.5;
  EXPECT_THROW(gauss_kmeans(n, p.areas, 2), std::invalid_argument);
  n(0, 0) = std::nan("");
  EXPECT_THROW(gauss_kmeans(n, p.areas, 2), std::invalid_argument);
}

TEST(GaussKmeans, SeedingDrawsByArea) {
  // Three directions 60 degrees apart, a and b with area 1, c with a billionth of it. Seeded by
  // area, the seeds are a and b (in either order) almost surely; c joins b, and a is a cluster of
  // its own whose centroid is a exactly. Seeded by count instead, c is a seed in two runs of three
  // and a ends in a mixed cluster (the final centroids then depend on the seeds; about 23% of
  // seeds would still give a alone). Over many seeds the difference cannot hide.
  Eigen::Matrix3Xd n(3, 3);
  n << Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0), Eigen::Vector3d(-0.5, std::sqrt(3.0) / 2, 0);
  const Eigen::Vector3d areas(1.0, 1.0, 1e-9);
  int a_alone = 0;
  const int runs = 200;
  for (int seed = 1; seed <= runs; ++seed) {
    GaussKmeansOptions o;
    o.seed = static_cast<std::uint32_t>(seed);
    const GaussKmeans r = gauss_kmeans(n, areas, 2, o);
    for (Eigen::Index c = 0; c < r.centroids.cols(); ++c)
      if ((r.centroids.col(c) - n.col(0)).norm() < 1e-12) ++a_alone;
  }
  EXPECT_GE(a_alone, runs * 95 / 100) << a_alone << " of " << runs;
}

TEST(GaussKmeans, EveryCentroidIsItsMembersAreaWeightedMean) {
  std::mt19937 rng(8);
  const Patch p = groups_around(test::random_normals_in_cap(rng, 4, Eigen::Vector3d::UnitZ(), M_PI), 25, 35 * kDeg, 9);
  for (int k = 1; k <= 5; ++k) {
    const GaussKmeans r = gauss_kmeans(p.normals, p.areas, k);
    if (!r.converged) continue;
    for (Eigen::Index c = 0; c < r.centroids.cols(); ++c) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      double weight = 0.0;
      for (Eigen::Index i = 0; i < p.normals.cols(); ++i)
        if (r.assignment(i) == c) sum += p.areas(i) * p.normals.col(i), weight += p.areas(i);
      if (weight == 0.0) continue;
      EXPECT_NEAR(r.cluster_weight(c), weight, 1e-12 * weight);
      EXPECT_LT((r.centroids.col(c) - sum.normalized()).norm(), 1e-9) << "k " << k << ", cluster " << c;
    }
  }
}
