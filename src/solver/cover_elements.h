// Internal: iARAP's elements on the tufted cover (src/intrinsic/tufted_cover.h) brought back to the input.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>

namespace iarap::detail {

// Rewrites elements built on the cover's vertices (traced_iarap_elements on TuftedCover::V and F) as
// elements of the input's num_vertices vertices: b's vertices and the cells through cover_vertex (the input
// vertex each cover vertex copies), the carrying face through input_face, and w halved, since the cover
// counts every face twice (front and back): on a closed oriented manifold the cover is two copies of it, and
// the halved elements give today's energy, L and rotations. Two halves that are the same element (the same
// cells and b up to sign, exactly) are merged into one of the summed weight. Rotation cells are the
// input's vertices; a vertex in no face keeps a cell with no elements. Call before finish_elements.
void fold_cover_elements(ArapElements& el, const Eigen::VectorXi& cover_vertex, int num_vertices);

} // namespace iarap::detail
