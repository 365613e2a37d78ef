// The print-size check: a part under 5 mm or over 1 m across is most likely in another unit.
#include <gtest/gtest.h>

#include <string>

#include "core/print/print_size.h"
#include "support/shapes.h"

using namespace slim;

namespace {

std::string warning_for(const Eigen::Vector3d& size) {
  return print_size_warning(test::box({-3, 7, 1}, Eigen::Vector3d(-3, 7, 1) + size).V).value_or("");
}

}  // namespace

TEST(PrintSize, PartsBetweenFiveMillimetresAndAMetreAreTakenAsTheyAre) {
  for (const Eigen::Vector3d size : {Eigen::Vector3d(5, 1, 1), Eigen::Vector3d(1, 60, 2), Eigen::Vector3d(3, 2, 1000)})
    EXPECT_EQ(warning_for(size), "") << size.transpose();
  EXPECT_FALSE(print_size_warning(Points(0, 3)).has_value());
}

TEST(PrintSize, ATinyPartIsLikelyInInchesCentimetresOrMetres) {
  const std::string w = warning_for({2.5, 1, 4.9});  // the largest extent decides
  EXPECT_NE(w.find("the part is 4.9 mm across at its largest, under 5 mm"), std::string::npos) << w;
  EXPECT_NE(w.find("inches (x 25.4)"), std::string::npos) << w;
  EXPECT_NE(w.find("metres (x 1000)"), std::string::npos) << w;
}

TEST(PrintSize, AHugePartIsLikelyAUnitlessExport) {
  const std::string w = warning_for({10, 1000.5, 20});
  EXPECT_NE(w.find("the part is 1000 mm across at its largest, over 1000 mm"), std::string::npos) << w;
  EXPECT_NE(w.find("unit-less export"), std::string::npos) << w;
}
