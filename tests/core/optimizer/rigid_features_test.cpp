// Rigid features (core/optimizer/rigid_features.h) through the whole optimizer: a feature that reaches the
// deviation budget holds there, in one piece, while the rest of the part goes on optimizing.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "core/optimizer/slimming.h"
#include "core/print/overhang.h"
#include "support/free_to_move.h"
#include "support/shapes.h"

using namespace slim;

#ifdef SLIM_TESTS_HAVE_VCG
namespace {

const Surface& bunny() { return test::sample_bunny(); }
double diag(const Surface& s) { return test::bbox_diagonal(s); }

// The faces whose three vertices lie above `share` of the height: the bunny's head and ears.
std::vector<bool> top_faces(const Surface& s, double share) {
  const double zmax = s.V.col(2).maxCoeff();
  std::vector<bool> marked(static_cast<size_t>(s.F.rows()), false);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    marked[static_cast<size_t>(f)] = (s.V(s.F(f, 0), 2) + s.V(s.F(f, 1), 2) + s.V(s.F(f, 2), 2)) / 3 > share * zmax;
  return marked;
}

std::vector<Eigen::Index> vertices_of(const Surface& s, const std::vector<bool>& faces) {
  std::vector<Eigen::Index> v;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (faces[static_cast<size_t>(f)])
      for (int k = 0; k < 3; ++k) v.push_back(s.F(f, k));
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// The largest distance of a point of `after` from the best rigid motion of `before` onto it
// (Kabsch: the rotation and translation that fit the points in the least-squares sense).
double rigid_fit_residual(const Points& before, const Points& after) {
  const Eigen::RowVector3d cb = before.colwise().mean(), ca = after.colwise().mean();
  const Eigen::MatrixXd B = before.rowwise() - cb, A = after.rowwise() - ca;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(B.transpose() * A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Matrix3d R = svd.matrixV() * D * svd.matrixU().transpose();
  return ((B * R.transpose()) - A).rowwise().norm().maxCoeff();
}

double risky_area_outside(const Surface& s, const std::vector<bool>& feature) {
  const OverhangReport r = analyse_overhang(s);
  const Eigen::VectorXd area = face_areas(s);
  double outside = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (r.risky[static_cast<size_t>(f)] && !feature[static_cast<size_t>(f)]) outside += area(f);
  return outside;
}

}  // namespace

TEST(RigidFeatures, AFeatureAtTheBudgetHoldsThereWhileTheRestGoesOn) {
  const Surface& s = bunny();
  const std::vector<bool> feature = top_faces(s, 0.75);
  const std::vector<Eigen::Index> fv = vertices_of(s, feature);
  ASSERT_GT(fv.size(), 50u);
  // The part free to move (test::free_to_move): held in place, the bunny's top would never
  // reach the budget.
  SlimmingOptions o = test::free_to_move();
  o.budget = DeviationBudget::from_percent(5.0);
  o.rigid_features = feature;
  // One voxel resolution: the property holds run by run, and the ladder returns one rung's run
  // bit for bit (resolution_ladder_test.cpp), so its other rungs would only repeat it.
  o.ladder.multiples.clear();
  const SlimmingResult r = slim_supports(s, o);
  // The feature reached the budget early, and the run went on past it.
  int first_held = 0;
  for (const IterationStats& st : r.history)
    if (st.features_held > 0 && first_held == 0) first_held = st.iteration;
  ASSERT_GT(first_held, 0) << "the feature never reached the budget: the test proves nothing";
  EXPECT_GT(r.iterations, first_held) << r.stop_reason;
  EXPECT_EQ(r.stop_reason.find("rigid feature"), std::string::npos) << r.stop_reason;
  // It stayed rigid, and within the budget.
  Points before(static_cast<Eigen::Index>(fv.size()), 3), after(static_cast<Eigen::Index>(fv.size()), 3);
  for (size_t i = 0; i < fv.size(); ++i) {
    before.row(static_cast<Eigen::Index>(i)) = s.V.row(fv[i]);
    after.row(static_cast<Eigen::Index>(i)) = r.surface.V.row(fv[i]);
  }
  EXPECT_LE(rigid_fit_residual(before, after), 1e-3 * diag(s));
  EXPECT_LE(r.displacement.maxCoeff(), 0.05 * diag(s) * (1 + 1e-9));
  // The rest kept improving after the feature stopped: less risky area outside the feature than
  // where the run stood when the feature first held.
  SlimmingOptions until_held = o;
  until_held.steps.max_iterations = first_held;
  const SlimmingResult early = slim_supports(s, until_held);
  EXPECT_LT(risky_area_outside(r.surface, feature), risky_area_outside(early.surface, feature));
  EXPECT_LT(r.after.risky_area, r.before.risky_area);
}
#endif
