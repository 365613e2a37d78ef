// A weighted quantile: the value below which a given share of the weight lies, as the crease
// figures' 99th percentile of the dihedral change, weighted by edge length (shape_metrics.h).
//
//   double p99 = weighted_quantile(values, weights, 0.99);
//
// Inputs:  values and weights, one each per item (any units; weights >= 0, in the same order),
//          q in [0, 1].
// Output:  the least value v such that the weights of the values up to v, walked in ascending
//          order, reach q of the total weight (the largest value if rounding keeps them short);
//          0 for no values.
// Cost: O(n) when the values above the answer are few (q near 1): only they are sorted, after a
// partial partition; the walk starts from the weight of the rest. A whole sort of the edges of a
// million-face mesh is far slower.
#pragma once

#include <vector>

namespace slim {

double weighted_quantile(const std::vector<double>& values, const std::vector<double>& weights, double q);

}  // namespace slim
