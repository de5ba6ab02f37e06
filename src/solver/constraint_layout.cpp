#include "constraint_layout.h"

#include "iarap/core/errors.h"

#include <string>

namespace iarap::detail {

namespace {

// free and free_slot from constrained_slot: every unknown not constrained, in increasing order.
void assign_free(ConstraintLayout& layout) {
  const int n = static_cast<int>(layout.constrained_slot.size());
  layout.free_slot = Eigen::VectorXi::Constant(n, -1);
  layout.free.reserve(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v)
    if (layout.constrained_slot[static_cast<size_t>(v)] < 0) {
      layout.free_slot(v) = static_cast<int>(layout.free.size());
      layout.free.push_back(v);
    }
}

} // namespace

ConstraintLayout constraint_layout(const ArapData& data, const Eigen::VectorXi& fixed,
                                   const ArapSoftConstraints& soft) {
  const int n = static_cast<int>(data.V.rows());
  if (fixed.size() == 0 && soft.size() == 0)
    throw InputError("ARAP: the constrained (fixed) vertex set is empty and there is no soft constraint");
  ConstraintLayout layout;
  layout.constrained_slot.assign(static_cast<size_t>(n), -1);
  std::vector<int>& slot = layout.constrained_slot;
  for (Eigen::Index k = 0; k < fixed.size(); ++k) {
    const int v = fixed(k);
    if (v < 0 || v >= n)
      throw InputError("ARAP: fixed[" + std::to_string(k) + "] = " + std::to_string(v) +
                       " is out of range; mesh has " + std::to_string(n) + " vertices");
    if (slot[v] >= 0)
      throw InputError("ARAP: fixed[" + std::to_string(k) + "] = " + std::to_string(v) + " repeats fixed[" +
                       std::to_string(slot[v]) + "]");
    slot[v] = static_cast<int>(k);
    layout.constrained.push_back(v);
  }

  // A component with no constrained vertex leaves L_ff singular (translations are free).
  std::vector<int> constrained_in(static_cast<size_t>(data.component_count), 0);
  std::vector<int> size_of(static_cast<size_t>(data.component_count), 0);
  std::vector<int> first_of(static_cast<size_t>(data.component_count), -1);
  for (int v = 0; v < n; ++v) {
    const int c = data.component(v);
    ++size_of[c];
    if (first_of[c] < 0) first_of[c] = v;
    if (slot[v] >= 0) ++constrained_in[c];
  }
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) ++constrained_in[data.component(soft.vertices(k))];
  for (Eigen::Index k = 0; k < soft.faces.size(); ++k)
    ++constrained_in[data.component(data.F(soft.faces(k), 0))];
  for (Eigen::Index k = 0; k < soft.hard_faces.size(); ++k)
    ++constrained_in[data.component(data.F(soft.hard_faces(k), 0))];
  // A vertex used by no face has no element: it is pinned where the initial guess puts it (the rest
  // position unless the caller moves it), so a mesh with unreferenced vertices deforms with them kept.
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (Eigen::Index f = 0; f < data.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<size_t>(data.F(f, k))] = 1;
  for (int c = 0; c < data.component_count; ++c) {
    if (constrained_in[c] > 0) continue;
    const bool isolated = size_of[c] == 1 && !used[static_cast<size_t>(first_of[c])];
    if (!data.pin_unconstrained_components && !isolated)
      throw SolverError("ARAP: connected component " + std::to_string(c) + " (" + std::to_string(size_of[c]) +
                        " vertices, e.g. vertex " + std::to_string(first_of[c]) +
                        ") has no constrained vertex or soft constraint, so the system is singular; "
                        "constrain one of its vertices "
                        "or enable pin_unconstrained_components");
    slot[first_of[c]] = static_cast<int>(layout.constrained.size());
    layout.constrained.push_back(first_of[c]);
    layout.pinned.push_back(first_of[c]);
  }

  assign_free(layout);
  return layout;
}

ConstraintLayout constraint_layout(Eigen::Index n, const std::vector<int>& constrained) {
  ConstraintLayout layout;
  layout.constrained = constrained;
  layout.constrained_slot.assign(static_cast<size_t>(n), -1);
  for (size_t k = 0; k < constrained.size(); ++k)
    layout.constrained_slot[static_cast<size_t>(constrained[k])] = static_cast<int>(k);
  assign_free(layout);
  return layout;
}

namespace {

// Calls emit(row, value) for column `column` of the symmetric L restricted to the free rows, renumbered
// (rows stay sorted because free_slot is increasing).
template <typename Emit>
void free_rows_of_column(const Eigen::SparseMatrix<double>& L, int column, const Eigen::VectorXi& free_slot,
                         Emit&& emit) {
  for (int k = L.outerIndexPtr()[column]; k < L.outerIndexPtr()[column + 1]; ++k) {
    const int row = free_slot(L.innerIndexPtr()[k]);
    if (row >= 0) emit(row, L.valuePtr()[k]);
  }
}

} // namespace

void split_system(const Eigen::SparseMatrix<double>& L, const ConstraintLayout& layout,
                  Eigen::SparseMatrix<double>& L_ff, Eigen::SparseMatrix<double>* L_fc) {
  auto build = [&](const std::vector<int>& columns, Eigen::SparseMatrix<double>& out) {
    const int nc = static_cast<int>(columns.size());
    out.resize(static_cast<Eigen::Index>(layout.free.size()), nc);
    int nnz = 0;
    for (int c = 0; c < nc; ++c)
      free_rows_of_column(L, columns[static_cast<size_t>(c)], layout.free_slot, [&](int, double) { ++nnz; });
    out.resizeNonZeros(nnz);
    int k = 0;
    out.outerIndexPtr()[0] = 0;
    for (int c = 0; c < nc; ++c) {
      free_rows_of_column(L, columns[static_cast<size_t>(c)], layout.free_slot, [&](int row, double value) {
        out.innerIndexPtr()[k] = row;
        out.valuePtr()[k++] = value;
      });
      out.outerIndexPtr()[c + 1] = k;
    }
  };
  build(layout.free, L_ff);
  if (L_fc) build(layout.constrained, *L_fc); // column j of symmetric L is row j: its free rows couple to j
}

void commit_layout(ArapData& data, const Eigen::VectorXi& fixed, ConstraintLayout& layout,
                   SparseCholesky& solver, Eigen::SparseMatrix<double>& L_fc) {
  data.solver = std::move(solver);
  data.L_fc.swap(L_fc); // Eigen 3.4's SparseMatrix has no move assignment: a "move" would copy
  data.fixed = fixed;
  data.pinned = Eigen::Map<const Eigen::VectorXi>(layout.pinned.data(),
                                                  static_cast<Eigen::Index>(layout.pinned.size()));
  data.free =
      Eigen::Map<const Eigen::VectorXi>(layout.free.data(), static_cast<Eigen::Index>(layout.free.size()));
  data.free_slot = std::move(layout.free_slot);
  data.free_rows.reset(); // of the old free set
}

} // namespace iarap::detail
