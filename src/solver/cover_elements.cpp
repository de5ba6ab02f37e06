#include "cover_elements.h"

#include "../intrinsic/tufted_cover.h"
#include "traced_elements.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace iarap::detail {

namespace {

// An element of two cells up to what leaves its energy term unchanged: the order of its cells and the sign
// of b (with s_hat = V^T b, (w/2) |U^T b - R s_hat|^2 is the same for -b). Cells ascending, b's non-zeros by
// vertex with the first one positive. The carrying face is left out: the front and the back copy of an edge
// may name the two faces beside it, and any face holding b's vertices serves the system's pattern.
struct ElementKey {
  int cell[2];
  int count;
  int index[3];
  double value[3];

  ElementKey(const ArapElements& el, Eigen::Index e) {
    cell[0] = std::min(el.cell[static_cast<size_t>(2 * e)], el.cell[static_cast<size_t>(2 * e + 1)]);
    cell[1] = std::max(el.cell[static_cast<size_t>(2 * e)], el.cell[static_cast<size_t>(2 * e + 1)]);
    count = 0;
    for (int k = 0; k < 3; ++k)
      if (el.b_value(e, k) != 0.0) {
        index[count] = el.b_index(e, k);
        value[count++] = el.b_value(e, k);
      }
    for (int i = 1; i < count; ++i) // at most three: insertion sort by vertex
      for (int j = i; j > 0 && index[j] < index[j - 1]; --j) {
        std::swap(index[j], index[j - 1]);
        std::swap(value[j], value[j - 1]);
      }
    const double sign = count > 0 && value[0] < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < count; ++i) value[i] *= sign;
    for (int i = count; i < 3; ++i) {
      index[i] = -1;
      value[i] = 0.0;
    }
  }

  // Lexicographic; equal keys are the same energy term, exactly.
  int compare(const ElementKey& o) const {
    const int a[] = {cell[0], cell[1], count, index[0], index[1], index[2]};
    const int b[] = {o.cell[0], o.cell[1], o.count, o.index[0], o.index[1], o.index[2]};
    for (int i = 0; i < 6; ++i)
      if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    for (int i = 0; i < 3; ++i)
      if (value[i] != o.value[i]) return value[i] < o.value[i] ? -1 : 1;
    return 0;
  }
};

} // namespace

void fold_cover_elements(ArapElements& el, const Eigen::VectorXi& cover_vertex, int num_vertices) {
  const Eigen::Index m = el.size();
  for (Eigen::Index e = 0; e < m; ++e) {
    // The three vertices of a cover face copy three distinct input vertices: b keeps its non-zeros apart.
    for (int k = 0; k < 3; ++k) el.b_index(e, k) = cover_vertex(el.b_index(e, k));
    el.w(e) *= 0.5;
    el.face[static_cast<size_t>(e)] = input_face(el.face[static_cast<size_t>(e)]);
  }
  for (int& c : el.cell) c = cover_vertex(c);
  el.num_vertices = el.num_cells = num_vertices;
  // Where the front and the back copy give the same element (an unflipped edge of a manifold region: b =
  // e_j - e_i exactly), the two halves become one element of the whole weight, so that the iterations visit
  // each once. Elements whose traces differ in roundoff stay two halves.
  std::vector<ElementKey> keys;
  keys.reserve(static_cast<size_t>(m));
  for (Eigen::Index e = 0; e < m; ++e) keys.emplace_back(el, e);
  std::vector<int> order(static_cast<size_t>(m));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return keys[static_cast<size_t>(a)].compare(keys[static_cast<size_t>(b)]) < 0;
  });
  std::vector<char> merged(static_cast<size_t>(m), 0);
  for (size_t i = 0; i < order.size();) {
    size_t j = i + 1;
    const int kept = order[i];
    for (; j < order.size() &&
           keys[static_cast<size_t>(order[j])].compare(keys[static_cast<size_t>(kept)]) == 0;
         ++j) {
      el.w(kept) += el.w(order[j]);
      merged[static_cast<size_t>(order[j])] = 1;
    }
    i = j;
  }
  if (std::count(merged.begin(), merged.end(), 1) > 0) drop_two_cell_elements(el, merged);
}

} // namespace iarap::detail
