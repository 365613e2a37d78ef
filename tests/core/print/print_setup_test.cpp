// The print setup (core/print/print_setup.h): the plate rule resolved for a part, the unit
// direction and tau, and the refusals of bad values before any work.
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/print/print_setup.h"

namespace slim {
namespace {

TEST(PrintSetup, ThePlateRuleResolvesForThePart) {
  EXPECT_DOUBLE_EQ(PlateRule::automatic().tolerance_mm(250.0).value(), 0.25);  // 1e-3 of the diagonal
  EXPECT_EQ(PlateRule::within(0.07).tolerance_mm(250.0).value(), 0.07);      // the part's size is not read
  EXPECT_EQ(PlateRule::within(0.0).tolerance_mm(250.0).value(), 0.0);
  EXPECT_FALSE(PlateRule::none().tolerance_mm(250.0).has_value());
  EXPECT_TRUE(PlateRule::automatic().is_automatic());
  EXPECT_FALSE(PlateRule::within(1.0).is_automatic());
  EXPECT_TRUE(PrintSetup{}.plate.is_automatic());
}

TEST(PrintSetup, ABadPlateToleranceIsRefused) {
  for (double bad : {-1e-9, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      PlateRule::within(bad).tolerance_mm(10.0);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("build plate tolerance"), std::string::npos) << e.what();
    }
  }
}

TEST(PrintSetup, TheRuleHasTheUnitDirectionAndTau) {
  PrintSetup setup;
  setup.direction = Eigen::Vector3d(0, 3, 4);
  setup.alpha_max_deg = 30.0;
  setup.plate = PlateRule::none();
  const PrintRule rule = print_rule(setup, 100.0);
  EXPECT_EQ(rule.d, Eigen::Vector3d(0, 0.6, 0.8));
  EXPECT_DOUBLE_EQ(rule.tau, 0.5);
  EXPECT_EQ(rule.alpha_max_deg, 30.0);
  EXPECT_FALSE(rule.plate_tolerance_mm.has_value());
  // The direction as every stage reads it: the same bits as unit_print_direction's.
  EXPECT_EQ(rule.d, unit_print_direction(setup.direction));
}

TEST(PrintSetup, BadDirectionsAndAnglesAreRefused) {
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(std::nan(""), 0, 1)}) {
    PrintSetup setup;
    setup.direction = d;
    EXPECT_THROW(print_rule(setup, 1.0), std::invalid_argument);
  }
  for (double alpha : {-5.0, 90.0, std::nan("")}) {
    PrintSetup setup;
    setup.alpha_max_deg = alpha;
    EXPECT_THROW(print_rule(setup, 1.0), std::invalid_argument) << alpha;
  }
}

}  // namespace
}  // namespace slim
