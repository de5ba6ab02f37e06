// Internal: the intrinsic Delaunay triangulation an operator needs, given by the caller or computed.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"

#include <Eigen/Core>
#include <optional>

namespace iarap::detail {

// Returns *precomputed after checking that its sizes match (V, F) (InputError naming the mismatch),
// else computes intrinsic_delaunay(V, F) into storage and returns it.
const IntrinsicDelaunay& intrinsic_for_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                            const IntrinsicDelaunay* precomputed,
                                            std::optional<IntrinsicDelaunay>& storage);

} // namespace iarap::detail
