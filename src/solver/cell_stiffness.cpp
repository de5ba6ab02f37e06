#include "cell_stiffness.h"

#include "iarap/core/errors.h"

#include "streamed_layout.h"
#include "visit_order.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace iarap::detail {

bool is_unit_stiffness(const Eigen::VectorXd& s) {
  return s.size() == 0 || (s.array() == 1.0).all();
}

Eigen::VectorXd cell_stiffness_of(const ArapElements& el, const Eigen::VectorXd& vertex_stiffness) {
  Eigen::VectorXd s(el.num_cells);
  s.head(el.num_vertices) = vertex_stiffness;
  for (int c = el.num_vertices; c < el.num_cells; ++c) {
    std::vector<int> reached;
    for (int k = el.cell_element_start[static_cast<size_t>(c)];
         k < el.cell_element_start[static_cast<size_t>(c) + 1]; ++k) {
      const int e = el.cell_element[static_cast<size_t>(k)];
      for (int j = 0; j < 3; ++j)
        if (el.b_value(e, j) != 0.0) reached.push_back(el.b_index(e, j));
    }
    std::sort(reached.begin(), reached.end());
    reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
    double sum = 0.0;
    for (const int v : reached) sum += vertex_stiffness(v);
    s(c) = reached.empty() ? 1.0 : sum / static_cast<double>(reached.size());
  }
  return s;
}

void apply_cell_stiffness(ArapElements& el, Eigen::VectorXd cell_stiffness) {
  auto sl = std::make_shared<StreamedLayout>(streamed(el));
  const auto cells = static_cast<int>(sl->cell_entry_start.size()) - 1;
  // Positions p of the visit order hold cell visit_order[p].
#pragma omp parallel for schedule(static)
  for (int p = 0; p < cells; ++p) {
    const double s = cell_stiffness(sl->visit_order[static_cast<size_t>(p)]);
    for (int k = sl->cell_entry_start[static_cast<size_t>(p)];
         k < sl->cell_entry_start[static_cast<size_t>(p) + 1]; ++k)
      sl->cell_entry[static_cast<size_t>(k)].w *= s;
  }
  const auto terms = static_cast<Eigen::Index>(sl->rhs_term.size());
#pragma omp parallel for schedule(static)
  for (Eigen::Index t = 0; t < terms; ++t) {
    RhsTerm& term = sl->rhs_term[static_cast<size_t>(t)];
    const double s = cell_stiffness(sl->visit_order[static_cast<size_t>(term.cell)]);
    for (int d = 0; d < 3; ++d) term.p[d] *= s; // a packed field: no double& to it
  }
  el.streamed = std::move(sl);
  el.cell_stiffness = std::move(cell_stiffness);
}

} // namespace iarap::detail
