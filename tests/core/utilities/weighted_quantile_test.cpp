// core/utilities/weighted_quantile.h against the plain definition: sort every value, walk up adding weights.
// Integer weights make every sum exact, so the two must agree to the bit whatever order they add.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "core/utilities/weighted_quantile.h"

using namespace slim;

namespace {

double by_full_sort(const std::vector<double>& values, const std::vector<double>& weights, double q) {
  if (values.empty()) return 0.0;
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  double sum = 0.0;
  for (size_t i : order) {
    sum += weights[i];
    if (sum >= q * total) return values[i];
  }
  return values[order.back()];
}

}  // namespace

TEST(WeightedQuantile, EqualsTheWalkUpAllValuesSorted) {
  std::mt19937 gen(3);
  std::exponential_distribution<double> change(0.5);
  std::uniform_int_distribution<int> weight(1, 9);
  for (size_t n : {size_t{1}, size_t{7}, size_t{1000}, size_t{5000}, size_t{200000}}) {
    std::vector<double> values(n), weights(n);
    for (size_t i = 0; i < n; ++i) values[i] = change(gen), weights[i] = weight(gen);
    for (double q : {0.0, 0.01, 0.5, 0.9, 0.99, 0.999, 1.0})
      EXPECT_EQ(weighted_quantile(values, weights, q), by_full_sort(values, weights, q)) << n << " values, q " << q;
  }
}

// The heaviest weights on the smallest values: the largest thirty-second of the values holds less
// than 1% of the weight, so the search must widen its tail to find the 99th percentile.
TEST(WeightedQuantile, HeavySmallValuesWidenTheSearch) {
  const size_t n = 100000;
  std::vector<double> values(n), weights(n);
  for (size_t i = 0; i < n; ++i) {
    values[i] = static_cast<double>((i * 7919) % n);  // every value once, shuffled
    weights[i] = values[i] < 0.9 * n ? 100.0 : 1.0;
  }
  const double expected = by_full_sort(values, weights, 0.99);
  EXPECT_LT(expected, n - n / 32.0);  // below the first tail the search sorts
  EXPECT_EQ(weighted_quantile(values, weights, 0.99), expected);
}

TEST(WeightedQuantile, TiesZeroWeightsAndNoValues) {
  EXPECT_EQ(weighted_quantile({}, {}, 0.99), 0.0);
  std::vector<double> values(5000, 2.0), weights(5000, 1.0);
  values[17] = 5.0;
  EXPECT_EQ(weighted_quantile(values, weights, 0.99), 2.0);
  EXPECT_EQ(weighted_quantile(values, weights, 1.0), 5.0);
  const std::vector<double> none(5000, 0.0);  // no weight at all: the least value, as the walk finds it
  EXPECT_EQ(weighted_quantile(values, none, 0.99), 2.0);
  EXPECT_EQ(weighted_quantile({3.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, 0.99), 1.0);
}
