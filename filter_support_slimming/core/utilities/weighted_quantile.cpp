#include "core/utilities/weighted_quantile.h"

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <utility>

namespace slim {

double weighted_quantile(const std::vector<double>& values, const std::vector<double>& weights, double q) {
  if (values.empty()) return 0.0;
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  std::vector<std::pair<double, double>> items(values.size());
  for (size_t i = 0; i < items.size(); ++i) items[i] = {values[i], weights[i]};
  const auto by_value = [](const std::pair<double, double>& a, const std::pair<double, double>& b) { return a.first < b.first; };
  // The largest `tail` values, apart: when the others weigh less than q of the total, the answer
  // is among them; else try four times as many, at last all of them.
  for (size_t tail = std::min(items.size(), std::max<size_t>(1024, items.size() / 32));; tail = std::min(items.size(), 4 * tail)) {
    const auto split = items.end() - static_cast<std::ptrdiff_t>(tail);
    std::nth_element(items.begin(), split, items.end(), by_value);
    double sum = 0.0;
    for (auto it = items.begin(); it != split; ++it) sum += it->second;
    if (!(sum >= q * total) || tail == items.size()) {
      std::sort(split, items.end(), by_value);
      for (auto it = split; it != items.end(); ++it) {
        sum += it->second;
        if (sum >= q * total) return it->first;
      }
      return items.back().first;
    }
  }
}

}  // namespace slim
