// Internal: iARAP's elements straight from the traced intrinsic edges, without the public Segments, in two
// steps so that arap_precompute can run the second beside the numeric factorization.
#pragma once
#include "iarap/solver/arap_elements.h"

#include "../intrinsic/trace_edges.h"

#include <vector>

namespace iarap::detail {

// The part of iarap_elements(V, intrinsic) that the system matrix needs (b, w, face, cells) and the rest
// vectors s_hat, for the IntrinsicDelaunay these traces make, built in one pass over the segments without
// storing them: every array arap_precompute does not fault in after the symbolic analysis is time iARAP
// pays over original ARAP. finish_elements(V, el, true) completes it, bit for bit equal to iarap_elements.
// SolverError names a segment whose end points share no input face.
ArapElements traced_iarap_elements(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri,
                                   const CompactTraces& traces);

// Removes the elements marked in drop (#E) from elements of two cells each with rest vectors (as
// traced_iarap_elements builds them), keeping the others in order; before finish_elements.
void drop_two_cell_elements(ArapElements& el, const std::vector<char>& drop);

// Fills the rest vectors s_hat (unless the builder did: has_rest_vectors), the transposed incidence
// (cell -> elements) and the streamed layout (visit order, cell entries, right-hand-side terms) from b, w and
// the element -> cell lists. Every builder ends with it; only the iterations read what it fills.
// release_arrays: the per-element arrays are released (release_element_arrays) as soon as the cell entries
// hold their values, before the right-hand side's terms are built: they and the whole layout are then never
// in memory at once (arap_precompute, when nothing after it reads them).
void finish_elements(const Eigen::MatrixXd& V, ArapElements& el, bool has_rest_vectors = false,
                     bool release_arrays = false);

// Throws InputError naming `what` when el's arrays were released (ArapElements::arrays_released).
void require_element_arrays(const ArapElements& el, const char* what);

} // namespace iarap::detail
