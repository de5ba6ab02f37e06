#include "streamed_layout.h"

#include "iarap/core/resident_memory.h"
#include "iarap/core/threads.h"

#include "visit_order.h"

#include <omp.h>

namespace iarap::detail {

namespace {

// The visit order, the rest positions in it and the cell entries: each cell's elements with their b (vertex
// positions in the visit order) and w side by side.
void fill_cell_entries(const Eigen::MatrixXd& V, const ArapElements& el, StreamedLayout& sl) {
  sl.visit_order = breadth_first_cell_order(el.num_vertices, el.num_cells, el.cell_element_start,
                                            el.cell_element, el.b_index.data(), V);
  const std::vector<int>& order = sl.visit_order;
  // The streamed arrays index cells and vertices by their positions in visit_order. They are filled in the
  // file's cell order, each cell's run written where its position puts it: the element arrays are then read
  // about as they lie in memory, and the scattering is one block per cell.
  const std::vector<int> position = inverse_permutation(sl.visit_order);
  const int n = el.num_vertices;
  sl.rest_rows.resize(n, 3);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int p = 0; p < n; ++p)
    for (int d = 0; d < 3; ++d) sl.rest_rows(p, d) = V(order[static_cast<size_t>(p)], d);
  sl.cell_entry_start.assign(static_cast<size_t>(el.num_cells) + 1, 0);
  for (int p = 0; p < el.num_cells; ++p) {
    const auto c = static_cast<size_t>(order[static_cast<size_t>(p)]);
    sl.cell_entry_start[static_cast<size_t>(p) + 1] =
        sl.cell_entry_start[static_cast<size_t>(p)] + el.cell_element_start[c + 1] - el.cell_element_start[c];
  }
  sl.cell_entry.resize(el.cell_element.size());
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int c = 0; c < el.num_cells; ++c) {
    CellEntry* entry =
        sl.cell_entry.data() + sl.cell_entry_start[static_cast<size_t>(position[static_cast<size_t>(c)])];
    for (int k = el.cell_element_start[static_cast<size_t>(c)];
         k < el.cell_element_start[static_cast<size_t>(c) + 1]; ++k, ++entry) {
      const int e = el.cell_element[static_cast<size_t>(k)];
      for (int j = 0; j < 3; ++j) {
        entry->index[j] = position[static_cast<size_t>(el.b_index(e, j))];
        entry->value[j] = el.b_value(e, j);
      }
      entry->w = el.w(e);
    }
  }
}

// The right-hand side's terms (RhsTerm) from the cell entries.
void fill_rhs_terms(const ArapElements& el, StreamedLayout& sl) {
  // The right-hand side's terms, cell by cell: each cell's entries are read in one forward sweep (they lie
  // side by side, as the local step reads them) and their contributions grouped by vertex; then every term
  // goes to its vertex's run. Each thread takes a range of cells and, in every vertex's run, the share its
  // cells hold there, after the shares of the ranges before it: a vertex's terms are then in cell order
  // whatever the number of threads. (Gathering them vertex by vertex through a vertex -> slot incidence read
  // an element's w, b, s_hat and cells from five places at every visit: beetle iARAP, finish_elements
  // 10.9-11.1 ms, now 7.8-8.1.) where[v]: v's slot among the current cell's terms, -1 none.
  const int n = el.num_vertices;
  sl.rhs_term_start.assign(static_cast<size_t>(n) + 1, 0);
  std::vector<std::vector<int>> share; // per thread: its count, then its next slot, in every vertex's run
  struct CellTerm {
    double p[3];
    int vertex;
  };
#pragma omp parallel num_threads(loop_thread_count())
  {
    const int threads = omp_get_num_threads(), thread = omp_get_thread_num();
#pragma omp single
    share.resize(static_cast<size_t>(threads));
    std::vector<int>& mine = share[static_cast<size_t>(thread)];
    mine.assign(static_cast<size_t>(n), 0);
    std::vector<int> where(static_cast<size_t>(n), -1);
    std::vector<CellTerm> terms;
    const int first = static_cast<int>(static_cast<long long>(el.num_cells) * thread / threads);
    const int last = static_cast<int>(static_cast<long long>(el.num_cells) * (thread + 1) / threads);
    // Calls add(v, w_e (b_e)_v, s_hat_e) for every non-zero of every element of the cell at position p.
    const double* rest = sl.rest_rows.data();
    auto for_each_contribution = [&](int p, const auto& add) {
      const CellEntry* entry = sl.cell_entry.data() + sl.cell_entry_start[static_cast<size_t>(p)];
      const CellEntry* end = sl.cell_entry.data() + sl.cell_entry_start[static_cast<size_t>(p) + 1];
      for (; entry != end; ++entry) {
        double s_hat[3];
        element_vector(*entry, rest, s_hat);
        for (int j = 0; j < 3; ++j)
          if (entry->value[j] != 0.0) add(entry->index[j], entry->w * entry->value[j], s_hat);
      }
    };
    for (int p = first; p < last; ++p) {
      for_each_contribution(p, [&](int v, double, const double(&)[3]) {
        if (where[static_cast<size_t>(v)] < 0) {
          where[static_cast<size_t>(v)] = 0;
          terms.push_back({{0.0, 0.0, 0.0}, v});
          ++mine[static_cast<size_t>(v)];
        }
      });
      for (const CellTerm& t : terms) where[static_cast<size_t>(t.vertex)] = -1;
      terms.clear();
    }
#pragma omp barrier
#pragma omp single
    {
      for (int v = 0; v < n; ++v) {
        int at = sl.rhs_term_start[static_cast<size_t>(v)];
        for (std::vector<int>& counts : share) {
          const int count = counts[static_cast<size_t>(v)];
          counts[static_cast<size_t>(v)] = at;
          at += count;
        }
        sl.rhs_term_start[static_cast<size_t>(v) + 1] = at;
      }
      sl.rhs_term.resize(static_cast<size_t>(sl.rhs_term_start[static_cast<size_t>(n)]));
    }
    for (int p = first; p < last; ++p) {
      for_each_contribution(p, [&](int v, double wb, const double(&s_hat)[3]) {
        int& at = where[static_cast<size_t>(v)];
        if (at < 0) {
          at = static_cast<int>(terms.size());
          terms.push_back({{0.0, 0.0, 0.0}, v});
        }
        for (int d = 0; d < 3; ++d) terms[static_cast<size_t>(at)].p[d] += wb * s_hat[d];
      });
      for (const CellTerm& t : terms) {
        where[static_cast<size_t>(t.vertex)] = -1;
        RhsTerm& term = sl.rhs_term[static_cast<size_t>(mine[static_cast<size_t>(t.vertex)]++)];
        for (int d = 0; d < 3; ++d) term.p[d] = t.p[d];
        term.cell = p;
      }
      terms.clear();
    }
  }
}

} // namespace

StreamedLayout streamed_layout(const Eigen::MatrixXd& V, ArapElements& el, bool release_arrays) {
  StreamedLayout sl;
  fill_cell_entries(V, el, sl);
  trace_resident("cell entries");
  if (release_arrays) {
    release_element_arrays(el);
    // Their heap pages back to the system before the terms are made: those of the arrays under malloc's
    // mapping threshold stayed resident beside the terms (692K vertices: ~60 MB).
    release_free_heap(el.num_vertices);
  }
  fill_rhs_terms(el, sl);
  trace_resident("rhs terms");
  return sl;
}

} // namespace iarap::detail
