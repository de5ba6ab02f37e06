// What an ArapData holds in memory, part by part (issue 44): the figures `bench` and `deform --report`
// print beside the process's peak resident set (core/resident_memory.h). Container sizes, counted from
// their capacities and CHOLMOD's allocation sizes: what the iterations keep, not the precompute's
// transient peak (the intrinsic triangulation, the traces), which only the peak resident set shows.
#pragma once
#include "iarap/solver/arap_types.h"

#include <cstddef>

namespace iarap {

struct ArapMemory {
  std::size_t mesh = 0;        // V, F, components, the fixed / pinned / free index arrays
  std::size_t elements = 0;    // ArapElements' arrays (b, s_hat, w, faces, cells and their transpose)
  std::size_t streamed = 0;    // the streamed layout the iterations read (cell entries, rhs terms, order)
  std::size_t system = 0;      // L, L_fc, the soft constraints' Q, the rigid groups' P, and L's free rows
                               // as the solves stream them (kept from the first solve on)
  std::size_t factor = 0;      // the Cholesky factor of L_ff (and of the rigid groups' K), solve plans
  std::size_t kept_matrix = 0; // the factorization's copies of L_ff and of its pattern (refactorization)
  std::size_t rotations = 0;   // R, one 3x3 per cell
  std::size_t total() const { return mesh + elements + streamed + system + factor + kept_matrix + rotations; }
};

ArapMemory arap_memory(const ArapData& data);

// Calls visit(name, bytes) for every part, then "total": the one list the reports are written from.
template <class Visit> void visit_arap_memory(const ArapMemory& m, Visit&& visit) {
  visit("mesh", m.mesh);
  visit("elements", m.elements);
  visit("streamed_layout", m.streamed);
  visit("system_matrix", m.system);
  visit("factor", m.factor);
  visit("kept_matrix", m.kept_matrix);
  visit("rotations", m.rotations);
  visit("total", m.total());
}

} // namespace iarap
