#include "iarap/solver/arap_memory.h"

#include "free_row_system.h"
#include "streamed_layout.h"

namespace iarap {

namespace {

template <class M> std::size_t dense_bytes(const M& m) {
  return static_cast<std::size_t>(m.size()) * sizeof(typename M::Scalar);
}

template <class T> std::size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t sparse_bytes(const Eigen::SparseMatrix<double>& A) {
  return static_cast<std::size_t>(A.data().allocatedSize()) * (sizeof(double) + sizeof(int)) +
         static_cast<std::size_t>(A.outerSize() + 1) * sizeof(int) +
         (A.isCompressed() ? 0 : static_cast<std::size_t>(A.outerSize()) * sizeof(int));
}

} // namespace

ArapMemory arap_memory(const ArapData& data) {
  ArapMemory m;
  m.mesh = dense_bytes(data.V) + dense_bytes(data.F) + dense_bytes(data.component) + dense_bytes(data.fixed) +
           dense_bytes(data.pinned) + dense_bytes(data.free) + dense_bytes(data.free_slot);
  const ArapElements& el = data.elements;
  m.elements = dense_bytes(el.b_index) + dense_bytes(el.b_value) + dense_bytes(el.s_hat) + dense_bytes(el.w) +
               vector_bytes(el.face) + vector_bytes(el.cell_start) + vector_bytes(el.cell) +
               vector_bytes(el.cell_element_start) + vector_bytes(el.cell_element) +
               dense_bytes(el.cell_stiffness) + vector_bytes(el.cell_neighbour_start) +
               vector_bytes(el.cell_neighbour);
  if (el.streamed) {
    const detail::StreamedLayout& sl = *el.streamed;
    m.streamed = vector_bytes(sl.visit_order) + dense_bytes(sl.rest_rows) +
                 vector_bytes(sl.cell_entry_start) + vector_bytes(sl.cell_entry) +
                 vector_bytes(sl.rhs_term_start) + vector_bytes(sl.rhs_term);
  }
  m.system =
      sparse_bytes(data.L) + sparse_bytes(data.L_fc) + sparse_bytes(data.Q) + sparse_bytes(data.rigid.P);
  if (data.free_rows) { // built by the first solve, kept for the next ones
    const detail::FreeRowSystem& rows = *data.free_rows;
    m.system += vector_bytes(rows.position) + vector_bytes(rows.free_position) +
                vector_bytes(rows.free_index) + vector_bytes(rows.row_start) + vector_bytes(rows.column) +
                vector_bytes(rows.value);
  }
  // With rigid groups the reduced system's factor counts beside L_ff's.
  m.factor = data.solver.factor_bytes() + data.rigid.solver.factor_bytes();
  m.kept_matrix = data.solver.kept_matrix_bytes() + data.rigid.solver.kept_matrix_bytes();
  m.rotations = vector_bytes(data.R);
  return m;
}

} // namespace iarap
