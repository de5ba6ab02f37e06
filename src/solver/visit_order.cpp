#include "visit_order.h"

#include <numeric>

namespace iarap::detail {

namespace {

// The cell -> vertices incidence that the search walks.
struct CellReads {
  int num_vertices;
  const std::vector<int>& cell_element_start;
  const std::vector<int>& cell_element;
  const int* b_index;
};

// Breadth-first search from the unplaced vertex `root`, appending what it reaches to `order`.
void breadth_first(const CellReads& g, int root, std::vector<char>& placed, std::vector<int>& order) {
  size_t head = order.size();
  placed[static_cast<size_t>(root)] = 1;
  order.push_back(root);
  while (head < order.size()) {
    const int c = order[head++];
    for (int k = g.cell_element_start[static_cast<size_t>(c)];
         k < g.cell_element_start[static_cast<size_t>(c) + 1]; ++k) {
      const int e = g.cell_element[static_cast<size_t>(k)];
      // Unused slots repeat a vertex of the element (ArapElements::b_index), so b_value need not be read.
      for (int j = 0; j < 3; ++j) {
        const int v = g.b_index[3 * static_cast<size_t>(e) + j];
        if (v >= g.num_vertices || placed[static_cast<size_t>(v)]) continue;
        placed[static_cast<size_t>(v)] = 1;
        order.push_back(v);
      }
    }
  }
}

} // namespace

std::vector<int> breadth_first_cell_order(int num_vertices, int num_cells,
                                          const std::vector<int>& cell_element_start,
                                          const std::vector<int>& cell_element, const int* b_index,
                                          const Eigen::MatrixXd& V) {
  const int n = num_vertices;
  const CellReads g{n, cell_element_start, cell_element, b_index};
  std::vector<int> order;
  order.reserve(static_cast<size_t>(num_cells));
  std::vector<char> placed(static_cast<size_t>(n), 0);
  if (n > 0) {
    // The first search starts at an extreme vertex along the bounding box's longest axis: an end of the
    // shape, so the fronts sweep across it (a second search from the first's last vertex would find a
    // better end at the price of another pass over the elements, which costs as much as this one).
    Eigen::Index axis = 0, first = 0;
    (V.colwise().maxCoeff() - V.colwise().minCoeff()).maxCoeff(&axis);
    V.col(axis).minCoeff(&first);
    breadth_first(g, static_cast<int>(first), placed, order);
  }
  for (int v = 0; v < n; ++v) // the other connected pieces, each from its first vertex in the file
    if (!placed[static_cast<size_t>(v)]) breadth_first(g, v, placed, order);
  // The inserted boundary cells read vertices but are read by none: they go last, in their own order.
  order.resize(static_cast<size_t>(num_cells));
  std::iota(order.begin() + n, order.end(), n);
  return order;
}

std::vector<int> inverse_permutation(const std::vector<int>& order) {
  std::vector<int> position(order.size());
  for (size_t p = 0; p < position.size(); ++p) position[static_cast<size_t>(order[p])] = static_cast<int>(p);
  return position;
}

} // namespace iarap::detail
