// The sparsity pattern shared by the system matrices of the three ARAP variants.
//
// Every element's b lives on the vertices of one input face (an edge, a face's edge, or a segment inside a
// face), so L = sum_e |cells(e)| w_e b_e b_e^T couples only vertices of a common face. Knowing the pattern
// from F alone lets the global step's symbolic factorization start before the elements exist (for iARAP:
// while the intrinsic triangulation is built) and lets L be summed in place without a triplet sort.
#pragma once
#include "iarap/mesh/edge_topology.h"
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iarap {

struct SystemPattern {
  // #V x #V, compressed, every (i, j) with i and j on a common face plus the whole diagonal; values 0.
  Eigen::SparseMatrix<double> matrix;
  // #F x 9: position in matrix.valuePtr() of entry (F(f,k), F(f,l)) at column 3 k + l.
  Eigen::Matrix<int, Eigen::Dynamic, 9, Eigen::RowMajor> face_slot;
};

// The pattern of F (#F x 3, indices in 0 .. num_vertices - 1, checked by the caller). O(#F + #V).
SystemPattern system_pattern(const Eigen::MatrixXi& F, int num_vertices);
// The same from the edge topology of F (edge_topology(F, num_vertices)) when the caller has it already.
SystemPattern system_pattern(const Eigen::MatrixXi& F, int num_vertices, const EdgeTopology& topology);

// Twice the cotan Laplacian of the input mesh, summed on the pattern from its face cotangents C (#F x 3,
// face_cotangents): sum_f sum_k C(f, k) (e_a - e_b)(e_a - e_b)^T over the edges (a, b) opposite corner k.
// It is original ARAP's L, and iARAP's 2 B^T D_w B as well (the segments of an intrinsic edge through a
// face, weighted by w_ij |e| / |s|, add up to that face's cotan form; checked in the solver tests), which
// lets arap_precompute factorize iARAP's L before the intrinsic triangulation exists.
Eigen::SparseMatrix<double> cotan_system_matrix(const Eigen::MatrixXi& F, const Eigen::MatrixXd& C,
                                                const SystemPattern& pattern);

// L = sum_e |cells(e)| w_e b_e b_e^T summed on the pattern through the slots of each element's face
// (elements.face). Same values as element_system_matrix(elements), plus explicit zeros where the pattern
// has entries no element touches. Throws InputError when an element's face is out of range or its b has a
// non-zero outside that face.
Eigen::SparseMatrix<double> element_system_matrix(const ArapElements& elements, const Eigen::MatrixXi& F,
                                                  const SystemPattern& pattern);

} // namespace iarap
