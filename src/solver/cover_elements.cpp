#include "cover_elements.h"

#include "../intrinsic/tufted_cover.h"

namespace iarap::detail {

void fold_cover_elements(ArapElements& el, const Eigen::VectorXi& cover_vertex, int num_vertices) {
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    // The three vertices of a cover face copy three distinct input vertices: b keeps its non-zeros apart.
    for (int k = 0; k < 3; ++k) el.b_index(e, k) = cover_vertex(el.b_index(e, k));
    el.w(e) *= 0.5;
    el.face[static_cast<size_t>(e)] = input_face(el.face[static_cast<size_t>(e)]);
  }
  for (int& c : el.cell) c = cover_vertex(c);
  el.num_vertices = el.num_cells = num_vertices;
}

} // namespace iarap::detail
