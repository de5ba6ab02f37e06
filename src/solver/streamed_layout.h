// What the iterations stream: the elements of ArapElements regrouped cell by cell, in a visit order of the
// cells and vertices. Internal to the solver: ArapElements::streamed holds one, filled by finish_elements.
//
// Cells and vertices are numbered in visit_order (num_cells: position -> cell; the #V vertices first, in a
// breadth-first order of the mesh, then the inserted boundary cells), and the iterations keep positions,
// rotations and the right-hand side in that order: neighbours then sit side by side in memory and are read
// while in cache, whatever the file's vertex order (1-to-4 subdivision, for one, numbers the midpoints far
// from their corners). No cell's sum changes with it: each cell's terms keep their order.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

// The two records below are packed to 4-byte alignment: 44 bytes instead of 48 and 28 instead of 32, some
// 55 bytes a vertex less (issue 44; x86 loads a double at any address, and the passes stream the records,
// so fewer bytes also means less memory traffic). Their doubles are read as fields, never through a double*.
#pragma pack(push, 4)

// One element of a cell: its b (vertex positions in visit_order) and w side by side, so that the local step
// reads a cell in one forward sweep. s_hat = V^T b is not stored: the passes recompute it from rest_rows
// with the same sum (rest_vector), bit for bit the value ArapElements::s_hat holds, for 24 bytes less an
// entry (some 150 bytes a vertex: issue 44). Left uninitialized when constructed (the builder writes each
// one): resizing the vectors then does not zero tens of megabytes that are overwritten at once.
struct CellEntry {
  CellEntry() {}
  int index[3];
  double value[3];
  double w;
};

// One term R_c p_vc of the right-hand side of a vertex v (Eq. 16 regrouped): p_vc = sum over the elements e
// of cell c with (b_e)_v != 0 of w_e (b_e)_v s_hat_e (a cell repeated in cells(e) counts as often), summed in
// element order. cell is a position in visit_order. Uninitialized when constructed, as CellEntry.
struct RhsTerm {
  RhsTerm() {}
  double p[3];
  int cell;
};

#pragma pack(pop)
static_assert(sizeof(CellEntry) == 3 * sizeof(int) + 4 * sizeof(double), "CellEntry is packed");
static_assert(sizeof(RhsTerm) == 3 * sizeof(double) + sizeof(int), "RhsTerm is packed");

struct StreamedLayout {
  std::vector<int> visit_order;
  // The rest positions V in visit order (#V x 3, row p: V's row visit_order[p]), the cell entries' b read
  // them for s_hat.
  ArapElements::ValueRows rest_rows;
  // The elements of the cell at position p: cell_entry[cell_entry_start[p] .. cell_entry_start[p + 1]), in
  // ArapElements::cell_element's order.
  std::vector<int> cell_entry_start;
  std::vector<CellEntry> cell_entry;
  // rhs_term_start (#V + 1) delimits the terms of the vertex at each position of visit_order, in increasing
  // cell position.
  std::vector<int> rhs_term_start;
  std::vector<RhsTerm> rhs_term;
};

// The layout of el from b, w, s_hat and the cell -> elements incidence (cell_element_start, cell_element),
// with the visit order from the rest positions V (#V x 3). The result does not depend on the thread count.
// release_arrays: el's per-element arrays are released (release_element_arrays) once the cell entries are
// filled, before the right-hand side's terms, which read the cell entries only.
StreamedLayout streamed_layout(const Eigen::MatrixXd& V, ArapElements& el, bool release_arrays);

// s = X^T b of entry x from row-major positions x_rows (#V x 3, visit order), summed in slot order: with
// rest_rows, s_hat exactly as ArapElements::s_hat sums it (arap_elements.cpp, set_rest_vector); with the
// current positions, the element vector of the local step (zero energy at rest, bit for bit).
inline void element_vector(const CellEntry& x, const double* x_rows, double (&s)[3]) {
  for (int d = 0; d < 3; ++d) {
    double v = 0.0;
    for (int k = 0; k < 3; ++k) v += x.value[k] * x_rows[3 * x.index[k] + d];
    s[d] = v;
  }
}

// s = X^T b and s_hat = V^T b of entry x (element_vector on x_rows, then on rest_rows).
inline void element_vectors(const CellEntry& x, const double* x_rows, const double* rest_rows, double (&s)[3],
                            double (&s_hat)[3]) {
  element_vector(x, x_rows, s);
  element_vector(x, rest_rows, s_hat);
}

// el's layout (finish_elements made it; not checked).
inline const StreamedLayout& streamed(const ArapElements& el) {
  return *el.streamed;
}

} // namespace iarap::detail
