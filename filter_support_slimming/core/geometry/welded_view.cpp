#include "core/geometry/welded_view.h"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace slim {

std::string WeldedView::vertex_number_note(const std::string& message) const {
  if (merged() == 0 || (message.find("vertex") == std::string::npos && message.find("edge") == std::string::npos))
    return "";
  return " (vertex numbers count each of the " + std::to_string(merged()) +
         " vertices that repeat an earlier vertex's position once: the mesh is checked with coincident vertices "
         "merged; face numbers are the mesh's own)";
}

Points WeldedView::positions_to_input(const Points& input_V, const Points& view_after) const {
  Points out = input_V;
  for (size_t i = 0; i < view_vertex.size(); ++i) {
    const int w = view_vertex[i];
    if ((view_after.row(w).array() != surface.V.row(w).array()).any()) out.row(static_cast<Eigen::Index>(i)) = view_after.row(w);
  }
  return out;
}

WeldedView weld_coincident(const Surface& s) {
  WeldedView view;
  const Eigen::Index n = s.V.rows();
  view.view_vertex.resize(static_cast<size_t>(n));
  std::iota(view.view_vertex.begin(), view.view_vertex.end(), 0);
  const bool indices_ok = s.F.size() == 0 || (s.F.minCoeff() >= 0 && s.F.maxCoeff() < n);
  if (!s.V.allFinite() || !indices_ok) {  // the core refuses it, naming the input's own vertex or face
    view.surface = s;
    return view;
  }
  // Sort by position (lexicographic, ties by index), so each group's first entry is its first
  // copy in input order. Equality is exact: -0 and +0 compare equal, which is the same point.
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) { return std::make_tuple(s.V(i, 0), s.V(i, 1), s.V(i, 2)); };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ka = key(a), kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  std::vector<int> first_copy(static_cast<size_t>(n));
  for (size_t k = 0; k < order.size(); ++k) {
    const bool same = k > 0 && key(order[k]) == key(order[k - 1]);
    first_copy[static_cast<size_t>(order[k])] = same ? first_copy[static_cast<size_t>(order[k - 1])] : order[k];
  }
  // Number the first copies in input order.
  std::vector<int> view_index(static_cast<size_t>(n), -1);
  int w = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (first_copy[static_cast<size_t>(i)] == i) view_index[static_cast<size_t>(i)] = w++;
  view.surface.V.resize(w, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int v = view_index[static_cast<size_t>(first_copy[static_cast<size_t>(i)])];
    view.view_vertex[static_cast<size_t>(i)] = v;
    if (first_copy[static_cast<size_t>(i)] == i) view.surface.V.row(v) = s.V.row(i);
  }
  view.surface.F.resize(s.F.rows(), 3);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) view.surface.F(f, k) = view.view_vertex[static_cast<size_t>(s.F(f, k))];
  return view;
}

}  // namespace slim
