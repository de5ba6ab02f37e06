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

// The two records below are packed to 4-byte alignment: 68 bytes instead of 72 and 28 instead of 32, some
// 55 bytes a vertex less (issue 44; x86 loads a double at any address, and the passes stream the records,
// so fewer bytes also means less memory traffic). Their doubles are read as fields, never through a double*.
#pragma pack(push, 4)

// One element of a cell: its b (vertex positions in visit_order), s_hat and w side by side, so that the local
// step reads a cell in one forward sweep. Left uninitialized when constructed (the builder writes each one):
// resizing the vectors then does not zero tens of megabytes that are overwritten at once.
struct CellEntry {
  CellEntry() {}
  int index[3];
  double value[3];
  double s_hat[3];
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
static_assert(sizeof(CellEntry) == 3 * sizeof(int) + 7 * sizeof(double), "CellEntry is packed");
static_assert(sizeof(RhsTerm) == 3 * sizeof(double) + sizeof(int), "RhsTerm is packed");

struct StreamedLayout {
  std::vector<int> visit_order;
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

// el's layout (finish_elements made it; not checked).
inline const StreamedLayout& streamed(const ArapElements& el) {
  return *el.streamed;
}

} // namespace iarap::detail
