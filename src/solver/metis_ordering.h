// Internal: the nested-dissection ordering of a symmetric pattern's graph, METIS called directly with the
// options chosen for the large meshes that use it (issue 44; docs/performance.md, "The BLAS and the
// ordering").
#pragma once
#include <Eigen/SparseCore>
#include <vector>

namespace iarap::detail {

// A fill-reducing permutation of the n x n symmetric `pattern` (only its entries below the diagonal are
// read; values ignored): perm[k] is the row eliminated k-th, for cholmod_analyze_p. Empty when METIS fails
// (CHOLMOD's own ordering then).
std::vector<int> metis_nested_dissection(const Eigen::SparseMatrix<double>& pattern);

} // namespace iarap::detail
