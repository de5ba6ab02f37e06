#include "visit_order.h"

#include <numeric>

namespace iarap::detail {

namespace {

// Breadth-first search from the unplaced vertex `root`, appending what it reaches to `order`.
void breadth_first(const ArapElements& el, int root, std::vector<char>& placed, std::vector<int>& order) {
  const int n = el.num_vertices;
  size_t head = order.size();
  placed[static_cast<size_t>(root)] = 1;
  order.push_back(root);
  while (head < order.size()) {
    const int c = order[head++];
    for (int k = el.cell_element_start[static_cast<size_t>(c)];
         k < el.cell_element_start[static_cast<size_t>(c) + 1]; ++k) {
      const int e = el.cell_element[static_cast<size_t>(k)];
      // Unused slots repeat a vertex of the element (ArapElements::b_index), so b_value need not be read.
      for (int j = 0; j < 3; ++j) {
        const int v = el.b_index(e, j);
        if (v >= n || placed[static_cast<size_t>(v)]) continue;
        placed[static_cast<size_t>(v)] = 1;
        order.push_back(v);
      }
    }
  }
}

} // namespace

std::vector<int> breadth_first_cell_order(const ArapElements& el, const Eigen::MatrixXd& V) {
  const int n = el.num_vertices;
  std::vector<int> order;
  order.reserve(static_cast<size_t>(el.num_cells));
  std::vector<char> placed(static_cast<size_t>(n), 0);
  if (n > 0) {
    // The first search starts at an extreme vertex along the bounding box's longest axis: an end of the
    // shape, so the fronts sweep across it (a second search from the first's last vertex would find a
    // better end at the price of another pass over the elements, which costs as much as this one).
    Eigen::Index axis = 0, first = 0;
    (V.colwise().maxCoeff() - V.colwise().minCoeff()).maxCoeff(&axis);
    V.col(axis).minCoeff(&first);
    breadth_first(el, static_cast<int>(first), placed, order);
  }
  for (int v = 0; v < n; ++v) // the other connected pieces, each from its first vertex in the file
    if (!placed[static_cast<size_t>(v)]) breadth_first(el, v, placed, order);
  // The inserted boundary cells read vertices but are read by none: they go last, in their own order.
  order.resize(static_cast<size_t>(el.num_cells));
  std::iota(order.begin() + n, order.end(), n);
  return order;
}

std::vector<int> visit_positions(const ArapElements& el) {
  std::vector<int> position(el.visit_order.size());
  for (size_t p = 0; p < position.size(); ++p)
    position[static_cast<size_t>(el.visit_order[p])] = static_cast<int>(p);
  return position;
}

void rotations_to_visit_order(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R,
                              std::vector<Eigen::Matrix3d>& out) {
  out.resize(static_cast<size_t>(el.num_cells));
  for (size_t p = 0; p < out.size(); ++p) out[p] = R[static_cast<size_t>(el.visit_order[p])];
}

void rotations_from_visit_order(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R,
                                std::vector<Eigen::Matrix3d>& out) {
  out.resize(static_cast<size_t>(el.num_cells));
  for (size_t p = 0; p < out.size(); ++p) out[static_cast<size_t>(el.visit_order[p])] = R[p];
}

} // namespace iarap::detail
