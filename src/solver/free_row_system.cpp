#include "free_row_system.h"

#include "soft_terms.h"
#include "streamed_layout.h"
#include "visit_order.h"

namespace iarap::detail {
namespace {

FreeRowSystem build_free_rows(const ArapData& data) {
  FreeRowSystem rows;
  rows.position = inverse_permutation(streamed(data.elements).visit_order);
  const std::vector<int>& position = rows.position;
  const Eigen::SparseMatrix<double> L_soft =
      data.Q.rows() > 0 ? with_soft(data.L, data.Q) : Eigen::SparseMatrix<double>();
  const Eigen::SparseMatrix<double>& L = data.Q.rows() > 0 ? L_soft : data.L;
  const Eigen::Index nf = data.free.size();
  std::vector<int> free_of_position(position.size(), -1);
  for (Eigen::Index i = 0; i < nf; ++i)
    free_of_position[static_cast<size_t>(position[static_cast<size_t>(data.free(i))])] = static_cast<int>(i);
  rows.free_position.reserve(static_cast<size_t>(nf));
  rows.free_index.reserve(static_cast<size_t>(nf));
  rows.row_start.reserve(static_cast<size_t>(nf) + 1);
  rows.row_start.push_back(0);
  for (size_t p = 0; p < free_of_position.size(); ++p) {
    const int i = free_of_position[p];
    if (i < 0) continue;
    rows.free_position.push_back(static_cast<int>(p));
    rows.free_index.push_back(i);
    // L is symmetric: its column data.free(i) is the row.
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, data.free(i)); it; ++it) {
      rows.column.push_back(position[static_cast<size_t>(it.row())]);
      rows.value.push_back(it.value());
    }
    rows.row_start.push_back(static_cast<int>(rows.column.size()));
  }
  return rows;
}

} // namespace

std::shared_ptr<const FreeRowSystem> free_row_system(ArapData& data) {
  // commit_layout and arap_set_soft_weights clear the cache; the size checks catch data whose L or free set
  // was replaced some other way.
  const FreeRowSystem* cached = data.free_rows.get();
  if (!cached || cached->free_index.size() != static_cast<size_t>(data.free.size()) ||
      cached->position.size() != static_cast<size_t>(data.elements.num_cells))
    data.free_rows = std::make_shared<const FreeRowSystem>(build_free_rows(data));
  return data.free_rows;
}

} // namespace iarap::detail
