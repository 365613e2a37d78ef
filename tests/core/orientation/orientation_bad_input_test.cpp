// Print Orientation (core/orientation/orientation.h) on bad input: a readable refusal for every malformed
// surface and option, and on the bad-input catalogue a sane pose or a refusal, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/orientation/orientation.h"
#include "support/bad_inputs.h"
#include "support/shapes.h"

namespace slim {

TEST(Orientation, BadInputsAreRefusedWithAReason) {
  using ::testing::HasSubstr;
  const Surface t = test::t_shape();
  auto refusal = [](const Surface& s, const OrientationOptions& o) -> std::string {
    try {
      optimize_orientation(s, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_THAT(refusal(Surface{}, {}), HasSubstr("no faces"));
  Surface nan = t;
  nan.V(3, 1) = std::nan("");
  EXPECT_THAT(refusal(nan, {}), HasSubstr("vertex 3"));
  Surface point = t;
  point.V.setConstant(2.0);
  EXPECT_THAT(refusal(point, {}), HasSubstr("zero extent"));
  Surface one_flipped = t;
  std::swap(one_flipped.F(0, 1), one_flipped.F(0, 2));
  EXPECT_THAT(refusal(one_flipped, {}), HasSubstr("not consistently oriented"));
  for (double alpha : {-1.0, 90.0, std::nan("")}) {
    OrientationOptions o;
    o.alpha_max_deg = alpha;
    EXPECT_THAT(refusal(t, o), HasSubstr("self-supporting angle"));
  }
  using Setting = void (*)(OrientationOptions&);
  const std::vector<std::pair<Setting, std::string>> settings{
      {[](OrientationOptions& o) { o.sphere_candidates = 0; }, "sphere directions"},
      {[](OrientationOptions& o) { o.contact_bonus = -0.1; }, "contact bonus"},
      {[](OrientationOptions& o) { o.plate = PlateRule::within(std::numeric_limits<double>::infinity()); }, "plate tolerance"},
      {[](OrientationOptions& o) { o.report_count = 0; }, "reported"},
      {[](OrientationOptions& o) { o.refine_starts = -1; }, "refined"},
      {[](OrientationOptions& o) { o.flat_regions = -1; }, "flat regions"},
      {[](OrientationOptions& o) { o.hull_facets = -1; }, "convex-hull facets"},
      {[](OrientationOptions& o) { o.distinct_deg = 181; }, "distinct candidates"},
      {[](OrientationOptions& o) { o.threads = -2; }, "thread count"}};
  for (const auto& [set, reason] : settings) {
    OrientationOptions o;
    set(o);
    EXPECT_THAT(refusal(t, o), HasSubstr(reason));
  }
  EXPECT_THROW(score_orientation(t, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(rotation_to_up(Eigen::Vector3d(std::nan(""), 0, 1)), std::invalid_argument);
}

TEST(Orientation, BadInputCatalogueIsOrientedOrRefused) {
  // The bad-input catalogue: every mesh either gets a sane result or a readable refusal, never a crash.
  for (const test::BadInput& c : test::bad_inputs()) {
    OrientationOptions o;
    if (c.options.print.alpha_max_deg >= 0.0 && c.options.print.alpha_max_deg < 90.0) o.alpha_max_deg = c.options.print.alpha_max_deg;
    try {
      const OrientationResult r = optimize_orientation(c.surface, o);
      EXPECT_TRUE(r.best.direction.allFinite() && std::abs(r.best.direction.norm() - 1.0) < 1e-12) << c.name;
      EXPECT_TRUE(std::isfinite(r.best.score)) << c.name;
      EXPECT_LE(r.best.score, r.as_given.score) << c.name;
      EXPECT_TRUE(apply_orientation(c.surface, r.rotation).V.allFinite()) << c.name;
    } catch (const std::invalid_argument& e) {
      EXPECT_GT(std::string(e.what()).size(), 20u) << c.name;
    }
  }
}

}  // namespace slim
