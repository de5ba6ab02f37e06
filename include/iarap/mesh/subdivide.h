// Midpoint (1-to-4) subdivision of a triangle mesh.
#pragma once
#include <Eigen/Core>

namespace iarap {

// Splits every face of (V #V x 3, F #F x 3) into four by its edge midpoints. V_out keeps the #V input
// vertices first, in order, followed by one midpoint per unique edge; every new face keeps its parent's
// orientation: (a, b, c) -> (a, m_ab, m_ca), (b, m_bc, m_ab), (c, m_ca, m_bc), (m_ab, m_bc, m_ca). Throws
// InputError for wrong column counts or out-of-range indices (naming the face).
void subdivide_midpoint(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::MatrixXd& V_out,
                        Eigen::MatrixXi& F_out);

// Applies subdivide_midpoint `times` times in place (benchmark meshes: each time 4x the faces).
void subdivide_midpoint(Eigen::MatrixXd& V, Eigen::MatrixXi& F, int times);

} // namespace iarap
