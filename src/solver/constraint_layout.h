// Which rows of the ARAP system are free and where the constrained ones go, and the system split along it
// (L_ff, L_fc): what arap_precompute and arap_set_fixed share. Internal to the solver.
#pragma once
#include "iarap/solver/arap_types.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace iarap::detail {

// Which vertices are free and where the constrained ones go: [fixed; pinned].
struct ConstraintLayout {
  std::vector<int> constrained_slot; // #V position in [fixed; pinned], or -1 for a free vertex
  std::vector<int> constrained;      // the constrained vertices in slot order
  std::vector<int> pinned;
  std::vector<int> free;     // increasing
  Eigen::VectorXi free_slot; // #V position in free, or -1
};

// The layout for the constrained set `fixed` (#fixed, 0-based) of data's mesh (data.V, data.F,
// data.component). A component with a soft or hard point (soft: checked, weights > 0) needs no constrained
// vertex: Q makes the system positive definite on its translations (1^T Q 1 = 2 W (sum_j c_j)^2 = 2 W per
// point). Throws InputError for an empty set without soft points, an index out of range or a duplicate
// (naming the position and the index), SolverError for a connected component without constrained vertex or
// soft point (naming the component, its size and one vertex) unless data.pin_unconstrained_components, which
// pins its first vertex instead. A vertex used by no face is pinned either way (layout.pinned): it has no
// energy and stays where the initial guess is.
ConstraintLayout constraint_layout(const ArapData& data, const Eigen::VectorXi& fixed,
                                   const ArapSoftConstraints& soft = {});

// The layout of n unknowns of which `constrained` (distinct, in 0..n-1; not checked) are held, in that slot
// order, nothing pinned: for a system that is not an ArapData's (constrained_solve.h).
ConstraintLayout constraint_layout(Eigen::Index n, const std::vector<int>& constrained);

// L (#V x #V, symmetric, compressed) split into L_ff (free x free) and L_fc (free x constrained) directly
// in compressed form. Matrices with one pattern give L_ff with one pattern, which is what lets the
// symbolic factorization run on the pattern ahead of the values.
void split_system(const Eigen::SparseMatrix<double>& L, const ConstraintLayout& layout,
                  Eigen::SparseMatrix<double>& L_ff, Eigen::SparseMatrix<double>* L_fc);

// Moves the factorization of L_ff, L_fc and the layout's vertex sets into data.
void commit_layout(ArapData& data, const Eigen::VectorXi& fixed, ConstraintLayout& layout,
                   SparseCholesky& solver, Eigen::SparseMatrix<double>& L_fc);

} // namespace iarap::detail
