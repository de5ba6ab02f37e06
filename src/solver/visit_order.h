// The order in which the iterations visit the rotation cells and the vertices: a breadth-first order of the
// mesh, so that cells visited one after the other read the same positions and rotations while they are
// still in cache; and the permutations between it and the file's order. Internal to the solver (the
// streamed layout, streamed_layout.h, is built in it).
#pragma once
#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

// A permutation of the num_cells cells (position -> cell): the num_vertices vertex cells first, in
// breadth-first order over "cell c reads vertex v" (v in b_e for an element e of c) from an extreme vertex
// of the rest mesh V (#V x 3), each further connected piece from its first vertex; then the inserted
// boundary cells (iARAP with refine_boundary) in their own order. The elements of cell c are
// cell_element[cell_element_start[c] .. cell_element_start[c + 1]); b_index holds 3 vertices per element,
// row-major (ArapElements::b_index; unused slots repeat a vertex of the element).
//
// Why: a file's vertex order is often far from local (1-to-4 subdivision numbers each edge's midpoint after
// all the corners; scanned or shuffled meshes worse), and the local step's gathers and the right-hand
// side's then miss the cache once the positions and rotations outgrow it. This is the Cuthill-McKee order
// without its per-level sort by degree, which matters for a band's width, not for a cache; it is written
// here because the libraries the project uses offer none (Boost.Graph has one; CHOLMOD's AMD and METIS
// orders reduce fill and are no locality order).
std::vector<int> breadth_first_cell_order(int num_vertices, int num_cells,
                                          const std::vector<int>& cell_element_start,
                                          const std::vector<int>& cell_element, const int* b_index,
                                          const Eigen::MatrixXd& V);

// The inverse permutation: position[order[p]] = p.
std::vector<int> inverse_permutation(const std::vector<int>& order);

// Per-cell values between the file's order and a visit order (order.size() each; out is resized):
// to_visit_order: out[p] = in[order[p]]; from_visit_order: out[order[p]] = in[p].
template <class T>
void to_visit_order(const std::vector<int>& order, const std::vector<T>& in, std::vector<T>& out) {
  out.resize(order.size());
  for (size_t p = 0; p < out.size(); ++p) out[p] = in[static_cast<size_t>(order[p])];
}
template <class T>
void from_visit_order(const std::vector<int>& order, const std::vector<T>& in, std::vector<T>& out) {
  out.resize(order.size());
  for (size_t p = 0; p < out.size(); ++p) out[static_cast<size_t>(order[p])] = in[p];
}

// The same permutations in place (values.size() == order.size()), by following each cycle of order; marks
// the visited positions in one bit each instead of a second array of the values: a solve's rotations go
// to the visit order and back without a spare copy (72 bytes a cell, issue 44).
// to_visit_order_in_place: values[p] becomes values[order[p]]; from_visit_order_in_place:
// values[order[p]] becomes values[p].
template <class T> void to_visit_order_in_place(const std::vector<int>& order, std::vector<T>& values) {
  std::vector<bool> done(order.size(), false);
  for (size_t start = 0; start < order.size(); ++start) {
    if (done[start]) continue;
    T first = values[start];
    size_t p = start;
    for (auto next = static_cast<size_t>(order[p]); next != start; next = static_cast<size_t>(order[p])) {
      values[p] = values[next];
      done[p] = true;
      p = next;
    }
    values[p] = first;
    done[p] = true;
  }
}
template <class T> void from_visit_order_in_place(const std::vector<int>& order, std::vector<T>& values) {
  std::vector<bool> done(order.size(), false);
  for (size_t start = 0; start < order.size(); ++start) {
    if (done[start]) continue;
    T carried = values[start]; // the value that goes to order[p], p the last position placed
    done[start] = true;
    for (auto p = static_cast<size_t>(order[start]); p != start; p = static_cast<size_t>(order[p])) {
      std::swap(carried, values[p]);
      done[p] = true;
    }
    values[start] = carried;
  }
}

} // namespace iarap::detail
